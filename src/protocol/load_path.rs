//! The load path of a finite-element run: what the load parameter does to the bilayer at each
//! state (`docs/model.md`, "Growth" and "Boundary conditions"). Every analysis follows the
//! strain `d` of the linear theory: under compression the end-shortening, with the right end
//! at `u_x = -L d`; under growth `d = 1 - 1/g`, with both ends held and the growing layers'
//! `Fg` set at `g`. The path owns the boundary conditions (the model's, [`model_conditions`]:
//! `u_x = 0` on `X = 0`, `u_x = -L d` on `X = L`, `u_y = 0` on `Y = -D`; the top is traction
//! free and `u_y` is free on both vertical edges), the right end's contact plane and the
//! materials at each `d`, so no caller needs to know which load it follows: [`Loading`] puts a
//! system at a load.

use crate::error::Result;
use crate::fem::{Dirichlet, System};
use crate::material::Bilayer;
use crate::mesh::{Mesh, BOTTOM, LEFT, RIGHT, X, Y};
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
        self.load().end_shortening(d)
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
}

/// A system that follows the bilayer's load path.
pub trait Loading {
    /// Puts the system at the load's strain `d` ([`System::set_load`]) and returns the boundary
    /// conditions at `d`.
    fn load_to(&mut self, d: f64) -> Result<Dirichlet>;
    /// What the load does to the bilayer.
    fn load_path(&self) -> LoadPath;
    /// The layer's growth `g` along `X` at the current load.
    fn layer_growth(&self) -> f64;
}

impl Loading for System {
    fn load_to(&mut self, d: f64) -> Result<Dirichlet> {
        let conditions = self.load_path().conditions(self.mesh(), d)?;
        self.set_load(d);
        Ok(conditions)
    }

    fn load_path(&self) -> LoadPath {
        LoadPath::new(self.unloaded_materials())
    }

    fn layer_growth(&self) -> f64 {
        self.load_path().materials_at(self.load()).layer.growth.stretches[0]
    }
}

/// The model's conditions at end-shortening `d`: `u_x = 0` at `X = 0`, `u_x = -L d` at `X = L`,
/// `u_y = 0` at `Y = -D`.
pub fn model_conditions(mesh: &Mesh, d: f64) -> Result<Dirichlet> {
    validate_compression("d", d)?;
    let (shift, dofs) = (-mesh.spec().length * d, mesh.dofs());
    let left = mesh.node_set(LEFT).iter().map(|&n| (dofs.dof(n, X), 0.0));
    let right = mesh.node_set(RIGHT).iter().map(|&n| (dofs.dof(n, X), shift));
    let bottom = mesh.node_set(BOTTOM).iter().map(|&n| (dofs.dof(n, Y), 0.0));
    Dirichlet::new(left.chain(right).chain(bottom).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshSpec;

    #[test]
    fn model_conditions_fix_both_edges_and_the_bottom() {
        let mesh = Mesh::new(MeshSpec::new(2, 1, 1, 3.0, 4.0, 3.0)).unwrap();
        let bc = model_conditions(&mesh, 0.25).unwrap();
        // 5 nodes per vertical edge (u_x) plus 5 bottom nodes (u_y).
        assert_eq!(bc.len(), 5 + 5 + 5);
        let right_x = mesh.dofs().dof(mesh.right()[3], X);
        let k = bc.dofs().iter().position(|&d| d == right_x).unwrap();
        assert_eq!(bc.values()[k], -1.0);
        assert!(model_conditions(&mesh, 1.0).is_err());
    }
}
