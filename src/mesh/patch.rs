//! A patch of tissue in three dimensions: 27-node hexahedra over the box `0 <= X <= Lx`,
//! `0 <= Z <= Lz`, `-D <= Y <= 1`, uniform in X and Z and, through the thickness, as the strip
//! ([`MeshSpec`]): uniform in the layer, graded geometrically in the substrate from `h0` at the
//! interface.
//!
//! Its sides are either periodic in X and Z (the nodes of `X = Lx` are those of `X = 0`, and
//! likewise in Z; an applied average stretch is carried across) or symmetry planes (node sets
//! [`LEFT`], [`RIGHT`], [`BACK`], [`FRONT`], on which the normal displacement is prescribed, as
//! on the strip's ends). Only this generator knows the grid: node `(i, j, k)` (along X, Y, Z)
//! is `(k cx + i) (2 ny + 1) + j`, with `cx` the node columns along X.

use super::{
    ElementKind, Face, Generator, Mesh, MeshSpec, Region, BACK, BOTTOM, FRONT, INTERFACE, LEFT, RIGHT, TOP, X, Z,
};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How the sides of a patch hold it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Sides {
    /// Periodic in X and Z, the average stretch carried across.
    #[default]
    #[value(help = "periodic in X and Z: u(X + Lx) = u(X) + (lambda_1 - 1) Lx, likewise in Z")]
    Periodic,
    /// Symmetry planes: the normal displacement prescribed on each side.
    #[value(help = "symmetry planes: the normal displacement prescribed on each side, as on the strip's ends")]
    Symmetry,
}

/// Size and grading of a patch, and the element on it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PatchSpec {
    /// Elements along X.
    pub nx: usize,
    /// Elements along Z.
    pub nz: usize,
    /// Length `Lx` along X.
    pub length_x: f64,
    /// Length `Lz` along Z.
    pub length_z: f64,
    /// Elements through the layer.
    pub layer_elements: usize,
    /// Elements through the substrate (graded).
    pub substrate_elements: usize,
    /// Thickness `h0` of the top substrate element.
    pub top_substrate_thickness: f64,
    /// Depth `D` of the substrate.
    pub depth: f64,
    pub sides: Sides,
    pub element: ElementKind,
}

impl PatchSpec {
    /// The through-thickness mesh, as the strip's.
    fn through_thickness(&self) -> MeshSpec {
        MeshSpec::new(
            self.nx,
            self.layer_elements,
            self.substrate_elements,
            self.top_substrate_thickness,
            self.length_x,
            self.depth,
        )
    }

    /// Checks counts and lengths; periodic sides need two elements along each direction.
    pub fn validate(&self) -> Result<()> {
        self.through_thickness().validate()?;
        let least = match self.sides {
            Sides::Periodic => 2,
            Sides::Symmetry => 1,
        };
        for (name, count) in [("patch.nx", self.nx), ("patch.nz", self.nz)] {
            if count < least {
                return Err(Error::invalid(
                    name,
                    count,
                    &format!("an integer >= {least} with {:?} sides", self.sides).to_lowercase(),
                ));
            }
        }
        for (name, value) in [("patch.length_x", self.length_x), ("patch.length_z", self.length_z)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(name, value, "(0, inf)"));
            }
        }
        Ok(())
    }

    /// Elements through the thickness.
    pub fn ny(&self) -> usize {
        self.layer_elements + self.substrate_elements
    }

    /// Number of hexahedra.
    pub fn num_elements(&self) -> usize {
        self.nx * self.ny() * self.nz
    }

    /// Number of unknowns (three per node; a periodic side's nodes are those of one side).
    pub fn num_dofs(&self) -> usize {
        let columns = |n: usize| match self.sides {
            Sides::Periodic => 2 * n,
            Sides::Symmetry => 2 * n + 1,
        };
        3 * columns(self.nx) * (2 * self.ny() + 1) * columns(self.nz)
    }
}

impl Mesh<3, 27> {
    /// The patch of `spec`.
    pub fn patch(spec: PatchSpec) -> Result<Self> {
        spec.validate()?;
        let periodic = spec.sides == Sides::Periodic;
        let (nx, ny, nz) = (spec.nx, spec.ny(), spec.nz);
        let columns = |n: usize| if periodic { 2 * n } else { 2 * n + 1 };
        let (cx, rows, cz) = (columns(nx), 2 * ny + 1, columns(nz));
        let element_rows = spec.through_thickness().element_rows();
        let node_y: Vec<f64> = (0..rows)
            .map(|j| match j % 2 {
                0 => element_rows[j / 2],
                _ => 0.5 * (element_rows[j / 2] + element_rows[j / 2 + 1]),
            })
            .collect();
        let node = |i: usize, j: usize, k: usize| (k * cx + i) * rows + j;
        let mut coordinates = vec![[0.0; 3]; cx * rows * cz];
        for k in 0..cz {
            for i in 0..cx {
                for (j, &y) in node_y.iter().enumerate() {
                    let x = spec.length_x * i as f64 / (2 * nx) as f64;
                    let z = spec.length_z * k as f64 / (2 * nz) as f64;
                    coordinates[node(i, j, k)] = [x, y, z];
                }
            }
        }
        let (mut elements, mut regions, mut wraps) = (Vec::new(), Vec::new(), Vec::new());
        for ez in 0..nz {
            for ex in 0..nx {
                for ey in 0..ny {
                    let mut wrap = [0u8; 27];
                    let nodes: [usize; 27] = std::array::from_fn(|local| {
                        let (mut i, j, mut k) = (2 * ex + local % 3, 2 * ey + (local / 3) % 3, 2 * ez + local / 9);
                        if i == cx {
                            (i, wrap[local]) = (0, wrap[local] | 1 << X);
                        }
                        if k == cz {
                            (k, wrap[local]) = (0, wrap[local] | 1 << Z);
                        }
                        node(i, j, k)
                    });
                    elements.push(nodes);
                    wraps.push(wrap);
                    regions.push(match ey < spec.substrate_elements {
                        true => Region::Substrate,
                        false => Region::Layer,
                    });
                }
            }
        }
        let layer = |j: usize| -> Vec<usize> {
            (0..cz)
                .flat_map(|k| (0..cx).map(move |i| (i, k)))
                .map(|(i, k)| node(i, j, k))
                .collect()
        };
        let mut node_sets = BTreeMap::from([
            (BOTTOM, layer(0)),
            (TOP, layer(rows - 1)),
            (INTERFACE, layer(2 * spec.substrate_elements)),
        ]);
        if !periodic {
            let side_x = |i: usize| (0..cz).flat_map(|k| (0..rows).map(move |j| node(i, j, k))).collect();
            let side_z = |k: usize| (0..cx).flat_map(|i| (0..rows).map(move |j| node(i, j, k))).collect();
            node_sets.extend([
                (LEFT, side_x(0)),
                (RIGHT, side_x(cx - 1)),
                (BACK, side_z(0)),
                (FRONT, side_z(cz - 1)),
            ]);
        }
        // The top face of each top element: its local nodes with eta = 1.
        let top_faces = (0..elements.len())
            .filter(|e| e % ny == ny - 1)
            .map(|element| Face {
                element,
                nodes: (0..27)
                    .filter(|local| (local / 3) % 3 == 2)
                    .map(|local| elements[element][local])
                    .collect(),
            })
            .collect();
        Ok(Mesh {
            generator: Generator::Patch(spec),
            element: spec.element,
            coordinates,
            elements,
            regions,
            node_sets,
            face_sets: BTreeMap::from([(TOP, top_faces)]),
            periods: match periodic {
                true => [spec.length_x, 0.0, spec.length_z],
                false => [0.0; 3],
            },
            wraps: if periodic { wraps } else { Vec::new() },
        })
    }

    /// The specification the patch was built from.
    pub fn patch_spec(&self) -> &PatchSpec {
        match &self.generator {
            Generator::Patch(spec) => spec,
            Generator::Strip(_) => unreachable!("three-dimensional meshes are patches"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{ElementKind, Y};

    fn spec(sides: Sides) -> PatchSpec {
        PatchSpec {
            nx: 3,
            nz: 2,
            length_x: 6.0,
            length_z: 4.0,
            layer_elements: 1,
            substrate_elements: 2,
            top_substrate_thickness: 2.0,
            depth: 5.0,
            sides,
            element: ElementKind::Displacement,
        }
    }

    #[test]
    fn a_periodic_patch_shares_its_sides_and_its_elements_see_them_one_period_on() {
        let mesh = Mesh::patch(spec(Sides::Periodic)).unwrap();
        // 6 x 7 x 4 nodes: no node at X = Lx or Z = Lz.
        assert_eq!(mesh.num_nodes(), 6 * 7 * 4);
        assert_eq!(mesh.elements().len(), 3 * 3 * 2);
        assert!(mesh.is_periodic() && !mesh.has_node_set(LEFT));
        assert!(mesh.coordinates().iter().all(|x| x[X] < 6.0 && x[Z] < 4.0));
        // Every element's own nodes form a box of its size, with its corners in order.
        let mut volume = 0.0;
        for e in 0..mesh.elements().len() {
            let x = mesh.element_coordinates(e);
            let size: [f64; 3] = std::array::from_fn(|c| x[26][c] - x[0][c]);
            assert!(
                (size[X] - 2.0).abs() < 1e-12 && (size[Z] - 2.0).abs() < 1e-12,
                "{e}: {size:?}"
            );
            assert!(size[Y] > 0.0);
            volume += size[X] * size[Y] * size[Z];
        }
        assert!((volume - 6.0 * 4.0 * 6.0).abs() < 1e-9, "{volume}");
        assert_eq!(mesh.top().len(), 6 * 4);
        assert!(mesh.top().iter().all(|&n| mesh.coordinates()[n][Y] == 1.0));
        assert!(mesh.bottom().iter().all(|&n| mesh.coordinates()[n][Y] == -5.0));
        assert_eq!(mesh.face_set(TOP).len(), 3 * 2);
        assert_eq!(mesh.regions().iter().filter(|r| **r == Region::Layer).count(), 6);
    }

    #[test]
    fn a_symmetric_patch_has_its_four_sides() {
        let mesh = Mesh::patch(spec(Sides::Symmetry)).unwrap();
        assert_eq!(mesh.num_nodes(), 7 * 7 * 5);
        assert!(!mesh.is_periodic());
        for (set, c, value) in [(LEFT, X, 0.0), (RIGHT, X, 6.0), (BACK, Z, 0.0), (FRONT, Z, 4.0)] {
            let nodes = mesh.node_set(set);
            assert!(nodes.iter().all(|&n| mesh.coordinates()[n][c] == value), "{set}");
        }
        assert_eq!(mesh.node_set(LEFT).len(), 5 * 7);
    }

    #[test]
    fn a_periodic_patch_needs_two_elements_a_side() {
        let message = Mesh::patch(PatchSpec {
            nz: 1,
            ..spec(Sides::Periodic)
        })
        .unwrap_err()
        .to_string();
        assert!(message.contains("patch.nz") && message.contains(">= 2"), "{message}");
        assert!(Mesh::patch(PatchSpec {
            nz: 1,
            ..spec(Sides::Symmetry)
        })
        .is_ok());
    }
}
