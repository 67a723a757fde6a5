//! The contact surface (the top `Y = 1`) and the search for contact pairs on its deformed shape.
//!
//! Two kinds of pair: a surface node against a plane (the symmetry planes: a trough that sits
//! on a symmetry plane closes against its own mirror image, which is contact with the plane),
//! and node-to-segment self-contact (slave: a surface node; master: the straight segment
//! between two consecutive surface nodes). Both passes are searched (every node is a slave),
//! which is symmetric in the two flanks of a trough. A slave is paired with the nearest segment
//! (distance to the segment itself) that it projects onto (`-0.1 <= xi <= 1.1`, see
//! `OVERHANG`), other than the two it belongs to, within `search_distance`, and only if the
//! normals oppose (`n_s . n_m < -1/2`): a node never meets its own flank, nor the far side of
//! the body. The gap is the signed distance to the segment's line.

use super::gap::{plane_gap, projection, segment_gap};
use crate::mesh::{DofMap, Mesh, TOP, X, Y};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A rigid plane `{x : n . x = c}`; `n` is the unit normal towards the open side.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    pub normal: [f64; 2],
    pub offset: f64,
    /// A symmetry plane through the first (`Some(First)`) or last surface node: the boundary
    /// conditions hold that node on the plane, so it is not a slave of this plane.
    pub holds: Option<End>,
}

/// An end of the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum End {
    First,
    Last,
}

impl Plane {
    /// The left symmetry plane `x >= position`, through the first surface node.
    pub fn left(position: f64) -> Self {
        Plane {
            normal: [1.0, 0.0],
            offset: position,
            holds: Some(End::First),
        }
    }

    /// The right symmetry plane `x <= position` (at `L (1 - d)`), through the last surface node.
    pub fn right(position: f64) -> Self {
        Plane {
            normal: [-1.0, 0.0],
            offset: -position,
            holds: Some(End::Last),
        }
    }

    /// Whether surface node `slave` of `count` may be a slave of this plane.
    fn admits(&self, slave: usize, count: usize) -> bool {
        match self.holds {
            Some(End::First) => slave != 0,
            Some(End::Last) => slave + 1 != count,
            None => true,
        }
    }
}

/// A contact pair. `slave` indexes the surface nodes; segment `j` joins surface nodes `j, j + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Pair {
    Plane { slave: usize, plane: usize },
    Segment { slave: usize, segment: usize },
}

impl Pair {
    /// The surface node that is the slave.
    pub fn slave(&self) -> usize {
        match *self {
            Pair::Plane { slave, .. } | Pair::Segment { slave, .. } => slave,
        }
    }

    /// The surface nodes involved: the slave, then the master segment's two nodes.
    pub fn surface_nodes(&self) -> Vec<usize> {
        match *self {
            Pair::Plane { slave, .. } => vec![slave],
            Pair::Segment { slave, segment } => vec![slave, segment, segment + 1],
        }
    }
}

/// The top surface: its nodes sorted by `X`, reference positions and tributary lengths.
#[derive(Clone, Debug)]
pub struct Surface {
    pub nodes: Vec<usize>,
    pub reference: Vec<[f64; 2]>,
    /// Reference length each node carries: the integral of its Q2 edge shape function,
    /// `h/6` at an element's corners and `2h/3` at its mid-side node (Simpson's weights).
    pub weights: Vec<f64>,
    /// The numbering of the mesh's unknowns.
    pub dof_map: DofMap,
}

impl Surface {
    /// The top surface `Y = 1` of `mesh`.
    pub fn top(mesh: &Mesh) -> Self {
        let nodes = mesh.node_set(TOP).to_vec();
        let reference: Vec<[f64; 2]> = nodes.iter().map(|&n| mesh.coordinates()[n]).collect();
        let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
        let mut weights = vec![0.0; nodes.len()];
        for face in mesh.face_set(TOP) {
            let [first, middle, last] = [0, 1, 2].map(|k| index[&face.nodes[k]]);
            let (a, b) = (reference[first], reference[last]);
            let h = (b[0] - a[0]).hypot(b[1] - a[1]);
            weights[first] += h / 6.0;
            weights[middle] += 2.0 * h / 3.0;
            weights[last] += h / 6.0;
        }
        Surface {
            nodes,
            reference,
            weights,
            dof_map: mesh.dofs(),
        }
    }

    /// Number of surface nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the surface has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Deformed positions `X + u` of the surface nodes.
    pub fn positions(&self, u: &[f64]) -> Vec<[f64; 2]> {
        self.nodes
            .iter()
            .zip(&self.reference)
            .map(|(&n, x)| [x[0] + u[self.dof_map.dof(n, X)], x[1] + u[self.dof_map.dof(n, Y)]])
            .collect()
    }

    /// Global unknowns `(x, y)` of every surface node of `pair`, in [`Pair::surface_nodes`] order.
    pub fn dofs(&self, pair: &Pair) -> Vec<usize> {
        pair.surface_nodes()
            .iter()
            .flat_map(|&i| self.dof_map.node_dofs(self.nodes[i]))
            .collect()
    }
}

/// Unit outward normal at each surface node, from the chord through its neighbours.
pub fn node_normals(x: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let last = x.len() - 1;
    (0..x.len())
        .map(|i| {
            let (a, b) = (x[i.saturating_sub(1)], x[(i + 1).min(last)]);
            let t = [b[0] - a[0], b[1] - a[1]];
            let norm = t[0].hypot(t[1]);
            [-t[1] / norm, t[0] / norm]
        })
        .collect()
}

/// Gap of `pair` at the deformed surface positions `x`.
pub fn gap(pair: &Pair, x: &[[f64; 2]], planes: &[Plane]) -> f64 {
    match *pair {
        Pair::Plane { slave, plane } => plane_gap(x[slave], planes[plane].normal, planes[plane].offset),
        Pair::Segment { slave, segment } => segment_gap(x[slave], x[segment], x[segment + 1]),
    }
}

/// How far (in segment lengths) beyond its ends a slave may project onto a master segment: a
/// slave facing a convex corner of the master surface projects just beyond both segments that
/// meet there, and must still find one.
const OVERHANG: f64 = 0.1;

/// All pairs within `distance_limit` of contact at the deformed positions `x` (module docs),
/// sorted. A slave keeps its segment in `previous` while that one still qualifies, so that a
/// slave facing a master node does not flip between the two segments that meet there.
pub fn find_pairs(
    x: &[[f64; 2]],
    planes: &[Plane],
    distance_limit: f64,
    self_contact: bool,
    previous: &[Pair],
) -> Vec<Pair> {
    let mut pairs = Vec::new();
    for slave in 0..x.len() {
        for (plane, p) in planes.iter().enumerate() {
            if p.admits(slave, x.len()) && plane_gap(x[slave], p.normal, p.offset) < distance_limit {
                pairs.push(Pair::Plane { slave, plane });
            }
        }
    }
    if self_contact && x.len() > 3 {
        let normals = node_normals(x);
        let kept: std::collections::HashMap<usize, usize> = previous
            .iter()
            .filter_map(|p| match *p {
                Pair::Segment { slave, segment } => Some((slave, segment)),
                Pair::Plane { .. } => None,
            })
            .collect();
        for (slave, n) in normals.iter().enumerate() {
            let near = |j: usize| {
                // Cheap rejection: farther than the limit from the segment's bounding box.
                let (a, b, p) = (x[j], x[j + 1], x[slave]);
                (0..2).all(|i| p[i] > a[i].min(b[i]) - distance_limit && p[i] < a[i].max(b[i]) + distance_limit)
            };
            let candidates = (0..x.len() - 1)
                .filter(|&j| j + 1 != slave && j != slave && near(j))
                .filter_map(|j| {
                    let (a, b) = (x[j], x[j + 1]);
                    let xi = projection(x[slave], a, b);
                    let t = [b[0] - a[0], b[1] - a[1]];
                    let facing = (n[1] * t[0] - n[0] * t[1]) / t[0].hypot(t[1]) < -0.5;
                    let outside = (-xi).max(xi - 1.0).max(0.0);
                    let c = xi.clamp(0.0, 1.0);
                    let distance = (x[slave][0] - a[0] - c * t[0]).hypot(x[slave][1] - a[1] - c * t[1]);
                    (outside <= OVERHANG && distance < distance_limit && facing).then_some((distance, outside, j))
                });
            let mut nearest: Option<(f64, f64, usize)> = None;
            for candidate in candidates {
                if kept.get(&slave) == Some(&candidate.2) {
                    nearest = Some((f64::NEG_INFINITY, 0.0, candidate.2));
                    break;
                }
                if nearest.is_none_or(|best| (candidate.0, candidate.1) < (best.0, best.1)) {
                    nearest = Some(candidate);
                }
            }
            if let Some((_, _, segment)) = nearest {
                pairs.push(Pair::Segment { slave, segment });
            }
        }
    }
    pairs.sort();
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A V-shaped trough with its tip at (1, 0): flanks from (1 -+ opening, 1), four segments each.
    fn trough(opening: f64) -> Vec<[f64; 2]> {
        let left = (0..=4).map(|i| [1.0 - opening * (1.0 - i as f64 / 4.0), 1.0 - i as f64 / 4.0]);
        let right = (1..=4).map(|i| [1.0 + opening * i as f64 / 4.0, i as f64 / 4.0]);
        left.chain(right).collect()
    }

    #[test]
    fn flanks_of_a_closing_trough_pair_up_and_flat_surfaces_do_not() {
        let x = trough(0.02);
        let pairs = find_pairs(&x, &[], 0.1, true, &[]);
        // Every node but the tip (index 4) faces the other flank.
        let slaves: Vec<usize> = pairs.iter().map(Pair::slave).collect();
        assert!(!slaves.contains(&4), "{pairs:?}");
        assert!(slaves.contains(&1) && slaves.contains(&7), "{pairs:?}");
        for pair in &pairs {
            let Pair::Segment { slave, segment } = *pair else {
                panic!()
            };
            assert!((slave < 4) != (segment < 4), "{pair:?} pairs a flank with itself");
            assert!(gap(pair, &x, &[]) > 0.0);
        }
        let flat: Vec<[f64; 2]> = (0..9).map(|i| [i as f64 * 0.1, 1.0]).collect();
        assert!(find_pairs(&flat, &[], 0.5, true, &[]).is_empty());
        // The end nodes are held on the symmetry planes and are no slaves of them.
        let near_wall = find_pairs(&flat, &[Plane::left(0.0), Plane::right(0.8)], 0.15, false, &[]);
        let expected = [(1, 0), (7, 1)].map(|(slave, plane)| Pair::Plane { slave, plane });
        assert_eq!(near_wall, expected);
    }
}
