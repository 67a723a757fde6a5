//! One solution state as a VTU file: the displacement as point data; `J`, Cauchy stress, von
//! Mises stress, fibre stretches and the layer id as element-centre cell data.

use super::StateFields;
use crate::error::Result;
use crate::fem::element::{PlaneElement, ReferenceElement};
use crate::fem::fields::{cell_fields, CellFields};
use crate::fem::System;
use crate::material::Bilayer;
use crate::mesh::{Mesh, X, Y};
use crate::output::vtu::{write_vtu, CellType, DataArray};
use std::path::Path;

/// The VTK cell of the mesh's element.
pub const CELL_TYPE: CellType<9> = CellType {
    vtk: PlaneElement::VTK_CELL_TYPE,
    order: PlaneElement::VTK_ORDER,
};

/// Writes the state `u` of `system` to `path`, with `extra` point data (e.g. a mode).
pub fn write_state(path: &Path, system: &System, materials: &Bilayer, u: &[f64], extra: Vec<DataArray>) -> Result<()> {
    let mesh = system.mesh();
    let (point_data, cell_data) = state_arrays(system, materials, u, extra)?;
    write_vtu(
        path,
        mesh.coordinates(),
        &CELL_TYPE,
        mesh.elements(),
        &point_data,
        &cell_data,
    )
}

/// The point data (the displacement, then `extra`) and cell data of the state `u` of `system`.
pub(super) fn state_arrays(
    system: &System,
    materials: &Bilayer,
    u: &[f64],
    extra: Vec<DataArray>,
) -> Result<(Vec<DataArray>, Vec<DataArray>)> {
    let mut point_data = vec![nodal_array("displacement", system.mesh(), u)];
    point_data.extend(extra);
    Ok((point_data, cell_arrays(cell_fields(system, materials, u)?)))
}

/// The nodal displacement part of the unknowns `u` of `mesh` as point data called `name`.
pub fn nodal_array(name: &str, mesh: &Mesh, u: &[f64]) -> DataArray {
    let dofs = mesh.dofs();
    let node = |n: usize| [u[dofs.dof(n, X)], u[dofs.dof(n, Y)]];
    DataArray::plane_vectors(name, (0..mesh.num_nodes()).map(node))
}

impl StateFields {
    /// Its point data as the snapshots': the displacement.
    pub fn point_arrays(&self) -> Vec<DataArray> {
        vec![displacement_array(self.displacement.iter().copied())]
    }

    /// Its cell data as the snapshots'.
    pub fn cell_arrays(&self) -> Vec<DataArray> {
        cell_arrays(self.cell.clone())
    }

    /// The nodes of every cell in VTK's order.
    pub fn vtk_cells(&self) -> Vec<[usize; 9]> {
        self.cells.iter().map(|c| CELL_TYPE.vtk_cell(c)).collect()
    }

    /// Writes the state as a snapshot's `.vtu` file.
    pub fn write_vtu(&self, path: &Path) -> Result<()> {
        write_vtu(
            path,
            &self.points,
            &CELL_TYPE,
            &self.cells,
            &self.point_arrays(),
            &self.cell_arrays(),
        )
    }
}

/// The nodal displacement as the snapshots' point data.
fn displacement_array(displacement: impl Iterator<Item = [f64; 2]>) -> DataArray {
    DataArray::plane_vectors("displacement", displacement)
}

/// The element-centre fields as the snapshots' cell data.
fn cell_arrays(fields: CellFields) -> Vec<DataArray> {
    let [stretch_1, stretch_2] = fields.fibre_stretch;
    vec![
        DataArray::scalars("J", fields.jacobian),
        DataArray::symmetric_tensors("cauchy_stress", &fields.cauchy),
        DataArray::scalars("von_mises", fields.von_mises),
        DataArray::scalars("pressure", fields.pressure),
        DataArray::scalars("fibre_stretch_1", stretch_1),
        DataArray::scalars("fibre_stretch_2", stretch_2),
        DataArray::scalars("layer", fields.layer),
        DataArray::scalars("growth", fields.growth),
        DataArray::scalars("elastic_J", fields.elastic_jacobian),
    ]
}
