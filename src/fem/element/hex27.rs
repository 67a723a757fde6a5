//! The 27-node triquadratic hexahedron: Lagrange shape functions on `[-1, 1]^3` and the 3x3x3
//! Gauss rule. Local node `a + 3 b + 9 c` sits at `(xi, eta, zeta) = (a - 1, b - 1, c - 1)`.

use super::quad9::{gauss_1d, lagrange, lagrange_derivative};
use super::ReferenceElement;

/// The 27-node hexahedron on `[-1, 1]^3`.
#[derive(Clone, Copy, Debug)]
pub struct Hex27;

impl ReferenceElement<3, 27, 27> for Hex27 {
    const NAME: &'static str = "27-node hexahedron";
    /// `VTK_TRIQUADRATIC_HEXAHEDRON`.
    const VTK_CELL_TYPE: u8 = 29;
    /// VTK's order: the corners (the bottom face `zeta = -1` counter-clockwise from
    /// `(-1, -1, -1)`, then the top), the mid-edge nodes of edges 0-1, 1-2, 2-3, 3-0, 4-5, 5-6,
    /// 6-7, 7-4, 0-4, 1-5, 2-6, 3-7, the face centres of `xi = -1, +1`, `eta = -1, +1`,
    /// `zeta = -1, +1`, and the centre.
    const VTK_ORDER: [usize; 27] = [
        0, 2, 8, 6, 18, 20, 26, 24, 1, 5, 7, 3, 19, 23, 25, 21, 9, 11, 17, 15, 12, 14, 10, 16, 4, 22, 13,
    ];
    /// The point `xi = eta = zeta = 0`, the middle of the 3x3x3 rule.
    const CENTRE: usize = 13;

    /// `N_a = l_(a mod 3)(xi) l_((a div 3) mod 3)(eta) l_(a div 9)(zeta)`.
    fn shape_functions(xi: [f64; 3]) -> [f64; 27] {
        let (lx, ly, lz) = (lagrange(xi[0]), lagrange(xi[1]), lagrange(xi[2]));
        std::array::from_fn(|a| lx[a % 3] * ly[(a / 3) % 3] * lz[a / 9])
    }

    fn shape_derivatives(xi: [f64; 3]) -> [[f64; 3]; 27] {
        let (lx, ly, lz) = (lagrange(xi[0]), lagrange(xi[1]), lagrange(xi[2]));
        let (dx, dy, dz) = (
            lagrange_derivative(xi[0]),
            lagrange_derivative(xi[1]),
            lagrange_derivative(xi[2]),
        );
        std::array::from_fn(|a| {
            let (i, j, k) = (a % 3, (a / 3) % 3, a / 9);
            [dx[i] * ly[j] * lz[k], lx[i] * dy[j] * lz[k], lx[i] * ly[j] * dz[k]]
        })
    }

    /// The 3x3x3 Gauss rule, exact for tri-quintic polynomials.
    fn quadrature() -> [([f64; 3], f64); 27] {
        let points = gauss_1d();
        std::array::from_fn(|g| {
            let ((x, wx), (y, wy), (z, wz)) = (points[g % 3], points[(g / 3) % 3], points[g / 9]);
            ([x, y, z], wx * wy * wz)
        })
    }

    fn node_coordinates(a: usize) -> [f64; 3] {
        [(a % 3) as f64 - 1.0, ((a / 3) % 3) as f64 - 1.0, (a / 9) as f64 - 1.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::ElementGeometry;

    #[test]
    fn shape_functions_are_a_partition_of_unity_interpolate_and_differentiate() {
        let (xi, h) = ([0.31, -0.77, 0.52], 1e-6);
        let (n, d) = (Hex27::shape_functions(xi), Hex27::shape_derivatives(xi));
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for r in 0..3 {
            assert!(d.iter().map(|g| g[r]).sum::<f64>().abs() < 1e-13);
            let shifted = |s: f64| {
                let mut x = xi;
                x[r] += s * h;
                Hex27::shape_functions(x)
            };
            let (plus, minus) = (shifted(1.0), shifted(-1.0));
            for a in 0..27 {
                assert!(((plus[a] - minus[a]) / (2.0 * h) - d[a][r]).abs() < 1e-9);
            }
        }
        for a in 0..27 {
            let at_node = Hex27::shape_functions(Hex27::node_coordinates(a));
            for (b, value) in at_node.iter().enumerate() {
                assert!((value - if a == b { 1.0 } else { 0.0 }).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn the_gauss_rule_integrates_tri_quintics() {
        let integral: f64 = Hex27::quadrature()
            .iter()
            .map(|(x, w)| w * x[0].powi(4) * x[1].powi(2) * x[2].powi(2))
            .sum();
        assert!((integral - 0.4 * (2.0 / 3.0) * (2.0 / 3.0)).abs() < 1e-15);
        assert_eq!(Hex27::quadrature()[Hex27::CENTRE].0, [0.0, 0.0, 0.0]);
    }

    /// VTK's hexahedron: corners, and the edges and faces as VTK lists them by corner.
    #[test]
    fn the_vtk_order_is_vtk_s_corners_edges_faces_and_centre() {
        let corners = [
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ];
        let at = |k: usize| Hex27::node_coordinates(Hex27::VTK_ORDER[k]);
        for (k, corner) in corners.iter().enumerate() {
            assert_eq!(at(k), *corner, "corner {k}");
        }
        let edges = [
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ];
        for (e, (i, j)) in edges.iter().enumerate() {
            let middle: [f64; 3] = std::array::from_fn(|c| 0.5 * (corners[*i][c] + corners[*j][c]));
            assert_eq!(at(8 + e), middle, "edge {i}-{j}");
        }
        let faces = [
            [0, 4, 7, 3],
            [1, 2, 6, 5],
            [0, 1, 5, 4],
            [3, 7, 6, 2],
            [0, 3, 2, 1],
            [4, 5, 6, 7],
        ];
        for (f, face) in faces.iter().enumerate() {
            let centre: [f64; 3] = std::array::from_fn(|c| face.iter().map(|&i| corners[i][c]).sum::<f64>() / 4.0);
            assert_eq!(at(20 + f), centre, "face {face:?}");
        }
        assert_eq!(at(26), [0.0, 0.0, 0.0]);
        let mut sorted = Hex27::VTK_ORDER;
        sorted.sort_unstable();
        assert_eq!(sorted, std::array::from_fn(|a| a));
    }

    /// A curved hexahedron: a linear field's gradient is exact at every Gauss point (the 3D
    /// inversion of `dX/dxi`), and a box's volume is its own.
    #[test]
    fn geometry_of_a_curved_hexahedron() {
        let nodes: [[f64; 3]; 27] = std::array::from_fn(|a| {
            let [x, y, z] = Hex27::node_coordinates(a);
            [
                1.3 * x + 0.2 * y + 0.05 * y * z,
                0.9 * y + 0.1 * x * z - 0.07 * x * x,
                0.8 * z + 0.06 * x * y + 0.1 * y,
            ]
        });
        let geometry = ElementGeometry::new::<Hex27>(&nodes).unwrap();
        let gradient = [[0.3, -0.2, 0.5], [0.1, 0.7, -0.4], [-0.6, 0.2, 0.9]];
        let field: Vec<[f64; 3]> = nodes
            .iter()
            .map(|x| std::array::from_fn(|i| (0..3).map(|j| gradient[i][j] * x[j]).sum()))
            .collect();
        for g in 0..27 {
            for (i, row) in gradient.iter().enumerate() {
                for (j, &expected) in row.iter().enumerate() {
                    let computed: f64 = geometry.gradients(g).iter().zip(&field).map(|(d, u)| u[i] * d[j]).sum();
                    assert!((computed - expected).abs() < 1e-12, "{computed} vs {expected}");
                }
            }
        }
        let box_nodes: [[f64; 3]; 27] = std::array::from_fn(|a| {
            let [x, y, z] = Hex27::node_coordinates(a);
            [2.0 * x, 0.5 * y + 1.0, 3.0 * z]
        });
        let volume = ElementGeometry::new::<Hex27>(&box_nodes).unwrap().volume();
        assert!((volume - 4.0 * 1.0 * 6.0).abs() < 1e-12, "{volume}");
        let inverted: [[f64; 3]; 27] = box_nodes.map(|[x, y, z]| [-x, y, z]);
        assert!(ElementGeometry::new::<Hex27>(&inverted).is_err());
    }
}
