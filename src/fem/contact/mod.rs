//! Contact of the top surface with the symmetry planes and with itself, by an augmented
//! Lagrangian ([`gap`]) on pairs found on the deformed surface ([`search`]), solved by
//! Newton's method inside Uzawa's multiplier updates ([`solve`], an outer loop of
//! [`crate::fem::equilibrium`]).
//!
//! Both vertical edges are symmetry planes, so a trough that sits on one of them closes
//! against its own mirror image: that self-contact is exactly contact of the surface with the
//! plane (`x >= 0` at `X = 0`, `x <= L (1 - d)` at `X = L`). Interior troughs close by
//! node-to-segment self-contact. Each pair is one group of an [`AddedEnergy`]; the tangent's
//! pattern is re-analysed only when a pair couples unknowns it does not couple yet, and it then
//! stores the neighbourhood of every node-to-segment pair in advance (a closing trough's next
//! pairs), so that a closing trough costs a few analyses, not one per new pair.

pub mod gap;
pub mod search;
pub mod solve;

pub use search::{End, Pair, Plane, Surface};
pub use solve::ContactUpdate;

use super::added::{AddedEnergy, Block};
use crate::error::{Error, Result};
use crate::mesh::{DofMap, Mesh, X, Y};
use gap::{differentiate, pair_energy, plane_gap, pressure, pressure_argument, segment_gap};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// The numbering of a pair's own unknowns by its surface nodes ([`Surface::dofs`]).
const PAIR_DOFS: DofMap = DofMap::PLANE;

/// Surface nodes on either side of a contact pair whose coupling the tangent's pattern stores
/// in advance ([`AddedEnergy::likely_groups`]).
const LIKELY_REACH: usize = 4;

/// Penalty, tolerance and search range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSettings {
    /// `eps`: pressure per unit penetration.
    pub penalty: f64,
    /// Largest penetration an accepted state may have (`1e-3 H`).
    pub tolerance: f64,
    /// Pairs closer than this (open or penetrating) are in the pattern.
    pub search_distance: f64,
    /// Largest number of Newton solves (multiplier updates) per state.
    pub max_augmentations: usize,
    /// Whether node-to-segment self-contact is searched (the planes always are).
    pub self_contact: bool,
}

impl ContactSettings {
    /// `eps = 100 mu / h` with `h` the smallest surface node spacing of `mesh` and `mu` the
    /// largest shear modulus: the penalty stiffness of a node, `w eps`, is then about `30-70 mu`,
    /// stiff enough that one or two multiplier updates reach the tolerance `1e-3 H`.
    pub fn for_mesh(mesh: &Mesh, mu: f64) -> Self {
        let x: Vec<f64> = mesh.top().iter().map(|&n| mesh.coordinates()[n][0]).collect();
        let h = x.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
        ContactSettings {
            penalty: 100.0 * mu / h,
            tolerance: 1e-3 * crate::mesh::LAYER_THICKNESS,
            search_distance: 0.5 * crate::mesh::LAYER_THICKNESS,
            max_augmentations: 12,
            self_contact: true,
        }
    }
}

/// What the contact looks like at one state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactState {
    /// Whether any pair carries pressure.
    pub in_contact: bool,
    /// Deformed length of the closed surface: segments with both nodes pressed, counted once
    /// against a plane and half against the surface (both flanks of a closed trough are listed).
    pub contact_length: f64,
    /// Number of separate closed zones (runs of pressed surface nodes).
    pub zones: usize,
    /// Largest penetration `max(0, -g)` over the pairs.
    pub penetration: f64,
    /// Nominal contact pressure (contact force per reference length) at every surface node.
    pub pressure: Vec<f64>,
}

/// The contact of the top surface of one mesh: pairs, multipliers and settings.
#[derive(Clone, Debug)]
pub struct Contact {
    pub settings: ContactSettings,
    surface: Surface,
    planes: Vec<Plane>,
    pairs: Vec<Pair>,
    groups: Vec<Vec<usize>>,
    /// Multiplier estimate `lambda` (nominal pressure) of every pair.
    multipliers: Vec<f64>,
}

/// What a resumed path needs of the contact: the planes where they are, the pairs and their
/// multipliers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactMemory {
    pub planes: Vec<Plane>,
    pub pairs: Vec<Pair>,
    pub multipliers: Vec<f64>,
}

/// Multipliers are kept per slave and target (a plane, or the surface): a slave that slides
/// onto the next segment keeps its pressure.
fn key(pair: &Pair) -> (usize, Option<usize>) {
    match *pair {
        Pair::Plane { slave, plane } => (slave, Some(plane)),
        Pair::Segment { slave, .. } => (slave, None),
    }
}

impl Contact {
    /// The top surface of `mesh` against `planes`, no pairs yet.
    pub fn new(mesh: &Mesh, planes: Vec<Plane>, settings: ContactSettings) -> Self {
        Contact {
            settings,
            surface: Surface::top(mesh),
            planes,
            pairs: Vec::new(),
            groups: Vec::new(),
            multipliers: Vec::new(),
        }
    }

    /// What a resumed path needs of it.
    pub fn memory(&self) -> ContactMemory {
        ContactMemory {
            planes: self.planes.clone(),
            pairs: self.pairs.clone(),
            multipliers: self.multipliers.clone(),
        }
    }

    /// Back to a state it had ([`Contact::memory`]) on the same surface.
    pub fn recall(&mut self, memory: ContactMemory) -> Result<()> {
        let nodes = self.surface.len();
        let fits = memory.planes.len() == self.planes.len()
            && memory.multipliers.len() == memory.pairs.len()
            && memory
                .pairs
                .iter()
                .all(|p| p.surface_nodes().iter().all(|&n| n < nodes));
        if !fits {
            return Err(Error::invalid(
                "checkpoint",
                "its contact pairs",
                "pairs of this run's surface",
            ));
        }
        self.groups = memory.pairs.iter().map(|p| self.surface.dofs(p)).collect();
        self.planes = memory.planes;
        self.pairs = memory.pairs;
        self.multipliers = memory.multipliers;
        Ok(())
    }

    /// The contact surface.
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The current pairs.
    pub fn pairs(&self) -> &[Pair] {
        &self.pairs
    }

    /// Moves plane `i` (e.g. the right symmetry plane to `L (1 - d)`).
    pub fn set_plane(&mut self, i: usize, plane: Plane) {
        self.planes[i] = plane;
    }

    /// Searches the pairs at `u`, keeping the multipliers of pairs that persist; true if changed.
    pub fn search(&mut self, u: &[f64]) -> bool {
        let x = self.surface.positions(u);
        let s = self.settings;
        let pairs = search::find_pairs(&x, &self.planes, s.search_distance, s.self_contact, &self.pairs);
        if pairs == self.pairs {
            return false;
        }
        let old: HashMap<_, f64> = self
            .pairs
            .iter()
            .map(key)
            .zip(self.multipliers.iter().copied())
            .collect();
        self.multipliers = pairs.iter().map(|p| old.get(&key(p)).copied().unwrap_or(0.0)).collect();
        self.groups = pairs.iter().map(|p| self.surface.dofs(p)).collect();
        self.pairs = pairs;
        true
    }

    /// Gap of every pair at `u`.
    pub fn gaps(&self, u: &[f64]) -> Vec<f64> {
        let x = self.surface.positions(u);
        self.pairs.iter().map(|p| search::gap(p, &x, &self.planes)).collect()
    }

    /// Largest penetration over the pairs at `u`.
    pub fn penetration(&self, u: &[f64]) -> f64 {
        self.gaps(u).into_iter().fold(0.0, |m, g| m.max(-g))
    }

    /// The pairs that carry pressure at `u`.
    pub fn loaded_pairs(&self, u: &[f64]) -> Vec<Pair> {
        let eps = self.settings.penalty;
        let gaps = self.gaps(u);
        (0..self.pairs.len())
            .filter(|&i| pressure(gaps[i], self.multipliers[i], eps) > 0.0)
            .map(|i| self.pairs[i])
            .collect()
    }

    /// Uzawa's update `lambda <- <lambda - eps g>_+` at the converged `u`.
    pub fn augment(&mut self, u: &[f64]) {
        let eps = self.settings.penalty;
        let gaps = self.gaps(u);
        for (lambda, g) in self.multipliers.iter_mut().zip(gaps) {
            *lambda = pressure(g, *lambda, eps);
        }
    }

    /// Pressures, closed length and penetration at `u`, an accepted state whose multipliers
    /// have been updated: each pair's pressure is then its multiplier.
    pub fn state(&self, u: &[f64]) -> ContactState {
        let n = self.surface.len();
        let x = self.surface.positions(u);
        let mut force = vec![[0.0; 2]; n];
        let mut on_plane = vec![false; n];
        let gaps = self.gaps(u);
        for (pair, (&lambda, dofs)) in self.pairs.iter().zip(self.multipliers.iter().zip(&self.groups)) {
            if lambda == 0.0 {
                continue;
            }
            // The pair pushes with `w lambda` along the gradient of its gap.
            let w = self.surface.weights[pair.slave()];
            let gradient = self.gap_gradient(pair, u, dofs);
            for (k, &node) in pair.surface_nodes().iter().enumerate() {
                force[node][0] += w * lambda * gradient[PAIR_DOFS.dof(k, X)];
                force[node][1] += w * lambda * gradient[PAIR_DOFS.dof(k, Y)];
            }
            on_plane[pair.slave()] |= matches!(pair, Pair::Plane { .. });
        }
        let pressure: Vec<f64> = force
            .iter()
            .zip(&self.surface.weights)
            .map(|(f, w)| f[0].hypot(f[1]) / w)
            .collect();
        let pressed: Vec<bool> = pressure.iter().map(|&p| p > 0.0).collect();
        let mut contact_length = 0.0;
        for j in 0..n.saturating_sub(1) {
            if pressed[j] && pressed[j + 1] {
                let share = if on_plane[j] && on_plane[j + 1] { 1.0 } else { 0.5 };
                contact_length += share * (x[j + 1][0] - x[j][0]).hypot(x[j + 1][1] - x[j][1]);
            }
        }
        let zones = (0..n).filter(|&i| pressed[i] && (i == 0 || !pressed[i - 1])).count();
        ContactState {
            in_contact: zones > 0,
            contact_length,
            zones,
            penetration: gaps.iter().fold(0.0, |m, &g| m.max(-g)),
            pressure,
        }
    }

    /// `dg/dx` of `pair`'s gap over its unknowns at `u`.
    fn gap_gradient(&self, pair: &Pair, u: &[f64], dofs: &[usize]) -> Vec<f64> {
        let position = |k: usize| self.position(pair, u, dofs, k);
        match *pair {
            Pair::Plane { plane, .. } => {
                let p = self.planes[plane];
                differentiate(|x| plane_gap([x[0], x[1]], p.normal, p.offset), position(0), false).gradient
            }
            Pair::Segment { .. } => {
                let (s, a, b) = (position(0), position(1), position(2));
                let x = [s[0], s[1], a[0], a[1], b[0], b[1]];
                differentiate(|x| segment_gap([x[0], x[1]], [x[2], x[3]], [x[4], x[5]]), x, false).gradient
            }
        }
    }

    /// Deformed position of the `k`-th surface node of `pair`.
    fn position(&self, pair: &Pair, u: &[f64], dofs: &[usize], k: usize) -> [f64; 2] {
        let r = self.surface.reference[pair.surface_nodes()[k]];
        [r[0] + u[dofs[PAIR_DOFS.dof(k, X)]], r[1] + u[dofs[PAIR_DOFS.dof(k, Y)]]]
    }

    /// The energy block of `pair` with multiplier `lambda` at `u`.
    fn block_of(&self, pair: &Pair, lambda: f64, u: &[f64], dofs: &[usize], with_tangent: bool) -> Block {
        let (eps, w) = (self.settings.penalty, self.surface.weights[pair.slave()]);
        let position = |k: usize| self.position(pair, u, dofs, k);
        match *pair {
            Pair::Plane { plane, .. } => {
                let p = self.planes[plane];
                differentiate(
                    |x| pair_energy(plane_gap([x[0], x[1]], p.normal, p.offset), lambda, eps, w),
                    position(0),
                    with_tangent,
                )
            }
            Pair::Segment { .. } => {
                let (s, a, b) = (position(0), position(1), position(2));
                differentiate(
                    |x| pair_energy(segment_gap([x[0], x[1]], [x[2], x[3]], [x[4], x[5]]), lambda, eps, w),
                    [s[0], s[1], a[0], a[1], b[0], b[1]],
                    with_tangent,
                )
            }
        }
    }
}

impl AddedEnergy for Contact {
    fn groups(&self) -> &[Vec<usize>] {
        &self.groups
    }

    /// A trough closes from its bottom up: the slaves within `LIKELY_REACH` surface nodes of
    /// a node-to-segment pair's slave soon face the segments within as many nodes of its
    /// segment.
    fn likely_groups(&self) -> Vec<Vec<usize>> {
        let last = self.surface.len() - 1;
        let around = |i: usize| i.saturating_sub(LIKELY_REACH)..=(i + LIKELY_REACH).min(last);
        self.pairs
            .iter()
            .filter_map(|pair| match *pair {
                Pair::Segment { slave, segment } => Some(
                    around(slave)
                        .chain(around(segment + 1))
                        .flat_map(|i| self.surface.dof_map.node_dofs(self.surface.nodes[i]))
                        .collect(),
                ),
                Pair::Plane { .. } => None,
            })
            .collect()
    }

    /// Where the first pair without pressure at `u` closes: its pressure argument
    /// `s = lambda - eps g` crosses 0, interpolated linearly between `u` and `trial`.
    fn switch_on_fraction(&self, u: &[f64], trial: &[f64]) -> f64 {
        let eps = self.settings.penalty;
        self.gaps(u)
            .into_iter()
            .zip(self.gaps(trial))
            .zip(&self.multipliers)
            .filter(|&((g0, _), &lambda)| pressure(g0, lambda, eps) == 0.0)
            .map(|((g0, g1), &lambda)| (pressure_argument(g0, lambda, eps), pressure_argument(g1, lambda, eps)))
            .filter(|&(_, s1)| s1 > 0.0)
            .fold(1.0, |m, (s0, s1)| m.min(s0 / (s0 - s1)))
    }

    fn block(&self, g: usize, u: &[f64], with_tangent: bool) -> Block {
        self.block_of(&self.pairs[g], self.multipliers[g], u, &self.groups[g], with_tangent)
    }
}
