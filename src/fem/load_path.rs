//! The load path of a finite-element run: what the load parameter does to the bilayer at each
//! state (`docs/model.md`, "Growth" and "Boundary conditions"). Every analysis follows the
//! strain `d` of the linear theory: under compression the end-shortening, with the right end
//! at `u_x = -L d`; under growth `d = 1 - 1/g`, with both ends held and the growing layers'
//! `Fg` set at `g`. The path owns the boundary conditions, the right end's contact plane, the
//! homogeneous reference state and the materials at each `d`, so no caller needs to know which
//! load it follows.

use super::boundary::{model_conditions, Dirichlet};
use crate::error::Result;
use crate::homogeneous::{homogeneous_state, HomogeneousState};
use crate::material::Bilayer;
use crate::mesh::Mesh;
use crate::parameters::{validate_compression, Load};

/// The bilayer under its load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadPath {
    /// The materials at `d = 0`, with the load they follow.
    materials: Bilayer,
}

impl LoadPath {
    pub fn new(materials: &Bilayer) -> Self {
        LoadPath { materials: *materials }
    }

    /// What loads the bilayer.
    pub fn load(&self) -> Load {
        self.materials.load
    }

    /// Whether the materials change along the path (a growth load).
    pub fn grows(&self) -> bool {
        self.materials.load.is_growth()
    }

    /// The materials at `d`: under growth, the grown layers.
    pub fn materials_at(&self, d: f64) -> Bilayer {
        self.materials.at_load(d).0
    }

    /// How far the right end has moved in, as a fraction of the length: `d` under compression,
    /// 0 under growth.
    pub fn end_shortening(&self, d: f64) -> f64 {
        if self.grows() {
            0.0
        } else {
            d
        }
    }

    /// The model's boundary conditions at `d` ([`model_conditions`] at the end-shortening).
    pub fn conditions(&self, mesh: &Mesh, d: f64) -> Result<Dirichlet> {
        validate_compression("d", d)?;
        model_conditions(mesh, self.end_shortening(d))
    }

    /// `X` of the right end's plane at `d` (the symmetry plane a surface node may not cross).
    pub fn right_plane(&self, mesh: &Mesh, d: f64) -> f64 {
        mesh.spec().length * (1.0 - self.end_shortening(d))
    }

    /// The homogeneous state at `d` (eq. 4, grown).
    pub fn reference(&self, d: f64) -> Result<HomogeneousState> {
        homogeneous_state(&self.materials, d)
    }
}
