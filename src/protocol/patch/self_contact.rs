//! Whether a patch's deformed top surface has passed through itself: the sign that two parts of
//! it have met (a fold's walls, say), which the patch does not model. The surface of each top
//! hexahedron (its 9 top nodes) is cut into 8 flat triangles; two triangles that share no node
//! cross where an edge of one passes through the other (Moller and Trumbore's segment test). On
//! periodic sides the neighbouring periods' copies of the surface are tested too; on symmetry
//! sides a top node past a side's plane has met its mirror image.

use crate::mesh::{Mesh, BACK, FRONT, LEFT, RIGHT, TOP, X, Z};
use std::collections::HashSet;

/// A flat triangle of the deformed surface: its corners and the mesh nodes they are.
struct Triangle {
    corners: [[f64; 3]; 3],
    nodes: [usize; 3],
    low: [f64; 3],
    high: [f64; 3],
}

impl Triangle {
    fn new(corners: [[f64; 3]; 3], nodes: [usize; 3]) -> Self {
        let low = std::array::from_fn(|c| corners.iter().map(|p| p[c]).fold(f64::INFINITY, f64::min));
        let high = std::array::from_fn(|c| corners.iter().map(|p| p[c]).fold(f64::NEG_INFINITY, f64::max));
        Triangle {
            corners,
            nodes,
            low,
            high,
        }
    }

    /// Whether the boxes around this triangle and `other` moved by `shift` overlap.
    fn near(&self, other: &Triangle, shift: [f64; 3]) -> bool {
        (0..3).all(|c| self.low[c] <= other.high[c] + shift[c] && other.low[c] + shift[c] <= self.high[c])
    }
}

/// Whether the deformed top surface of the state `u` crosses itself; `gradient` is the average
/// displacement gradient periodic sides carry (`u = H X + w` with `w` the unknowns there).
pub fn surface_crosses_itself(mesh: &Mesh<3, 27>, u: &[f64], gradient: &[[f64; 3]; 3]) -> bool {
    if !mesh.is_periodic() && crosses_a_side(mesh, u) {
        return true;
    }
    let triangles = surface_triangles(mesh, u, gradient);
    // The deformed periods: a periodic surface meets its neighbours' copies too.
    let shifts: Vec<[f64; 3]> = match mesh.is_periodic() {
        false => vec![[0.0; 3]],
        true => {
            let [length_x, _, length_z] = *mesh.periods();
            let (px, pz) = (length_x * (1.0 + gradient[X][X]), length_z * (1.0 + gradient[Z][Z]));
            (-1..=1)
                .flat_map(|i| (-1..=1).map(move |k| [i as f64 * px, 0.0, k as f64 * pz]))
                .collect()
        }
    };
    triangles.iter().enumerate().any(|(i, a)| {
        triangles[i..].iter().any(|b| {
            !a.nodes.iter().any(|n| b.nodes.contains(n))
                && shifts.iter().any(|&shift| a.near(b, shift) && cross(a, b, shift))
        })
    })
}

/// Whether a top node of a patch with symmetry sides has passed through a side's plane (where
/// the side's nodes are held): there the surface meets its mirror image.
fn crosses_a_side(mesh: &Mesh<3, 27>, u: &[f64]) -> bool {
    let dofs = mesh.dofs();
    let deformed = |n: usize, c: usize| mesh.coordinates()[n][c] + u[dofs.dof(n, c)];
    let plane = |set: &str, c: usize| {
        let nodes = mesh.node_set(set);
        nodes.iter().map(|&n| deformed(n, c)).sum::<f64>() / nodes.len() as f64
    };
    let spec = mesh.patch_spec();
    [(LEFT, RIGHT, X, spec.length_x), (BACK, FRONT, Z, spec.length_z)]
        .into_iter()
        .any(|(low, high, c, length)| {
            let (from, to) = (plane(low, c), plane(high, c));
            let slack = 1e-9 * length;
            mesh.node_set(TOP)
                .iter()
                .any(|&n| deformed(n, c) < from - slack || deformed(n, c) > to + slack)
        })
}

/// The 8 triangles of each top hexahedron's deformed top face.
fn surface_triangles(mesh: &Mesh<3, 27>, u: &[f64], gradient: &[[f64; 3]; 3]) -> Vec<Triangle> {
    let top: HashSet<usize> = mesh.node_set(TOP).iter().copied().collect();
    let dofs = mesh.dofs();
    let mut triangles = Vec::new();
    for (e, nodes) in mesh.elements().iter().enumerate() {
        let reference = mesh.element_coordinates(e);
        let mut face: Vec<(usize, [f64; 3])> = (0..27)
            .filter(|&a| top.contains(&nodes[a]))
            .map(|a| {
                let x = reference[a];
                let moved = std::array::from_fn(|c| {
                    x[c] + u[dofs.dof(nodes[a], c)] + (0..3).map(|j| gradient[c][j] * x[j]).sum::<f64>()
                });
                (a, moved)
            })
            .collect();
        if face.len() != 9 {
            continue;
        }
        // A 3 x 3 grid of the face's nodes by their reference X, then Z.
        face.sort_by(|p, q| {
            let (x, y) = (reference[p.0], reference[q.0]);
            x[X].total_cmp(&y[X]).then(x[Z].total_cmp(&y[Z]))
        });
        let at = |i: usize, k: usize| face[3 * i + k];
        for i in 0..2 {
            for k in 0..2 {
                let quad = [at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1)];
                for [p, q, r] in [[0, 1, 2], [0, 2, 3]] {
                    triangles.push(Triangle::new(
                        [quad[p].1, quad[q].1, quad[r].1],
                        [nodes[quad[p].0], nodes[quad[q].0], nodes[quad[r].0]],
                    ));
                }
            }
        }
    }
    triangles
}

/// Whether triangles `a` and `b` (moved by `shift`) cross: an edge of either passes through the
/// other.
fn cross(a: &Triangle, b: &Triangle, shift: [f64; 3]) -> bool {
    let moved: [[f64; 3]; 3] = std::array::from_fn(|v| std::array::from_fn(|c| b.corners[v][c] + shift[c]));
    let edges = |t: &[[f64; 3]; 3]| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
    edges(&a.corners).iter().any(|&(p, q)| segment_crosses(p, q, &moved))
        || edges(&moved).iter().any(|&(p, q)| segment_crosses(p, q, &a.corners))
}

/// Whether the segment `p q` passes through the triangle `t` (Moller and Trumbore, 1997).
fn segment_crosses(p: [f64; 3], q: [f64; 3], t: &[[f64; 3]; 3]) -> bool {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let crossed = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let (direction, e1, e2) = (sub(q, p), sub(t[1], t[0]), sub(t[2], t[0]));
    let h = crossed(direction, e2);
    let det = dot(e1, h);
    if det.abs() < 1e-14 * dot(e1, e1).max(dot(direction, direction)) {
        return false;
    }
    let s = sub(p, t[0]);
    let v = dot(s, h) / det;
    if !(0.0..=1.0).contains(&v) {
        return false;
    }
    let r = crossed(s, e1);
    let w = dot(direction, r) / det;
    if w < 0.0 || v + w > 1.0 {
        return false;
    }
    let along = dot(e2, r) / det;
    (0.0..=1.0).contains(&along)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Sides, Y};

    fn mesh(sides: Sides) -> Mesh<3, 27> {
        super::super::small_patch(sides)
    }

    /// The top nodes of the rows `X = a, a + 1, a + 2` moved by `shift` along X, the middle row
    /// down to `Y = 0.5` and the others up to 1.5: the edge between the first two rows then
    /// passes through the flat surface `shift` further on.
    fn folded(mesh: &Mesh<3, 27>, a: f64, shift: f64) -> Vec<f64> {
        let dofs = mesh.dofs();
        let mut u = vec![0.0; mesh.num_dofs()];
        for &n in mesh.node_set(TOP) {
            let x = mesh.coordinates()[n];
            let row = x[X] - a;
            if (-0.1..2.1).contains(&row) {
                u[dofs.dof(n, X)] = shift;
                u[dofs.dof(n, Y)] = if (row - 1.0).abs() < 0.1 { -0.5 } else { 0.5 };
            }
        }
        u
    }

    /// A wrinkled surface, however deep, does not cross itself; one folded through itself
    /// does, on periodic and on symmetry sides; on symmetry sides one through a side's plane
    /// meets its mirror image; on periodic sides one across the periodic side crosses the next
    /// period's copy of the surface.
    #[test]
    fn a_surface_folded_through_itself_is_found_and_a_wrinkled_one_is_not() {
        let none = [[0.0; 3]; 3];
        for sides in [Sides::Periodic, Sides::Symmetry] {
            let mesh = mesh(sides);
            let dofs = mesh.dofs();
            let mut wrinkled = vec![0.0; mesh.num_dofs()];
            for (n, x) in mesh.coordinates().iter().enumerate() {
                wrinkled[dofs.dof(n, Y)] = 2.0 * (std::f64::consts::PI * x[X] / 4.0).cos();
            }
            assert!(!surface_crosses_itself(&mesh, &wrinkled, &none), "{sides:?}");
            // Rows 3, 4, 5 moved to 0.5, 1.5, 2.5: the edge from row 3 to row 4 crosses Y = 1 at
            // X = 1, over the unmoved element between X = 0 and 2.
            assert!(
                surface_crosses_itself(&mesh, &folded(&mesh, 3.0, -2.5), &none),
                "{sides:?}"
            );
            assert!(
                !surface_crosses_itself(&mesh, &folded(&mesh, 3.0, 0.0), &none),
                "{sides:?}"
            );
        }
        // On symmetry sides, top nodes next to X = 0 moved past it meet their mirror images.
        let symmetric = mesh(Sides::Symmetry);
        let dofs = symmetric.dofs();
        let mut through = vec![0.0; symmetric.num_dofs()];
        for &n in symmetric.node_set(TOP) {
            if (symmetric.coordinates()[n][X] - 1.0).abs() < 1e-9 {
                through[dofs.dof(n, X)] = -1.2;
            }
        }
        assert!(surface_crosses_itself(&symmetric, &through, &none));
        through.iter_mut().for_each(|v| *v *= 0.5);
        assert!(!surface_crosses_itself(&symmetric, &through, &none));
        // Rows 6 and 7 (the next, X = 8, is row 0) moved to 8.5 and 9.5: the crossing lies over
        // X = 9, in the next period's copy of the unmoved element between X = 0 and 2.
        let mesh = mesh(Sides::Periodic);
        assert!(surface_crosses_itself(&mesh, &folded(&mesh, 6.0, 2.5), &none));
        assert!(!surface_crosses_itself(&mesh, &folded(&mesh, 6.0, 0.0), &none));
    }
}
