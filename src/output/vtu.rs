//! VTK XML unstructured grids (`.vtu`) of meshes of one cell type, and ParaView
//! collections (`.pvd`) that list them against a "time" (here the end-shortening `d`).
//!
//! Arrays are written inline in VTK's `binary` format: base64 of a `UInt64` byte count followed
//! by the little-endian values: exact, no float formatting, and a fifth smaller than ASCII.
//!
//! The cell type and VTK's order of its nodes come from the element ([`CellType`]). Points are
//! written in 3D (plane ones with `z = 0`).

use crate::error::{Error, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The cells' VTK type with `N` nodes each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellType<const N: usize> {
    /// VTK's cell type number.
    pub vtk: u8,
    /// VTK's node `k` is the cell's local node `order[k]`.
    pub order: [usize; N],
}

impl<const N: usize> CellType<N> {
    /// A cell's nodes (in the element's local order) in VTK's order.
    pub fn vtk_cell(&self, cell: &[usize; N]) -> [usize; N] {
        self.order.map(|local| cell[local])
    }
}

/// A named array of point or cell data: `values` holds `components` numbers per entity.
#[derive(Clone, Debug)]
pub struct DataArray {
    pub name: String,
    pub components: usize,
    pub values: Vec<f64>,
}

impl DataArray {
    /// One number per entity.
    pub fn scalars(name: &str, values: Vec<f64>) -> Self {
        DataArray {
            name: name.into(),
            components: 1,
            values,
        }
    }

    /// Plane vectors, padded to 3D with a zero third component (as ParaView expects).
    pub fn plane_vectors(name: &str, vectors: impl Iterator<Item = [f64; 2]>) -> Self {
        DataArray {
            name: name.into(),
            components: 3,
            values: vectors.flat_map(|[x, y]| [x, y, 0.0]).collect(),
        }
    }

    /// Vectors of three components.
    pub fn vectors(name: &str, vectors: impl Iterator<Item = [f64; 3]>) -> Self {
        DataArray {
            name: name.into(),
            components: 3,
            values: vectors.flatten().collect(),
        }
    }

    /// Symmetric tensors `[s11, s12, s22, s33]` in VTK's 6-component order XX, YY, ZZ, XY, YZ, XZ.
    pub fn symmetric_tensors(name: &str, tensors: &[[f64; 4]]) -> Self {
        DataArray {
            name: name.into(),
            components: 6,
            values: tensors
                .iter()
                .flat_map(|&[s11, s12, s22, s33]| [s11, s22, s33, s12, 0.0, 0.0])
                .collect(),
        }
    }
}

/// Writes `path` with the given points, cells of `cell_type` (in the element's local node
/// order) and data. Arrays of the wrong length are a bug (panic); non-finite values are refused.
pub fn write_vtu<const D: usize, const N: usize>(
    path: &Path,
    points: &[[f64; D]],
    cell_type: &CellType<N>,
    cells: &[[usize; N]],
    point_data: &[DataArray],
    cell_data: &[DataArray],
) -> Result<()> {
    for (arrays, count) in [(point_data, points.len()), (cell_data, cells.len())] {
        for array in arrays {
            assert_eq!(
                array.values.len(),
                array.components * count,
                "length of `{}`",
                array.name
            );
            if array.values.iter().any(|v| !v.is_finite()) {
                return Err(Error::NonFinite(format!(
                    "`{}` written to {}",
                    array.name,
                    path.display()
                )));
            }
        }
    }
    super::atomic::write_atomically(path, |temporary| {
        let io = |e| Error::io(path, e);
        let mut out = BufWriter::new(File::create(temporary).map_err(io)?);
        write_grid(&mut out, points, cell_type, cells, point_data, cell_data).map_err(io)?;
        out.flush().map_err(io)
    })
}

fn write_grid<const D: usize, const N: usize>(
    out: &mut impl Write,
    points: &[[f64; D]],
    cell_type: &CellType<N>,
    cells: &[[usize; N]],
    point_data: &[DataArray],
    cell_data: &[DataArray],
) -> std::io::Result<()> {
    writeln!(out, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        out,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
    )?;
    writeln!(out, "<UnstructuredGrid>")?;
    writeln!(
        out,
        r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
        points.len(),
        cells.len()
    )?;
    writeln!(out, "<Points>")?;
    let coordinates: Vec<f64> = points
        .iter()
        .flat_map(|p| (0..3).map(move |c| if c < D { p[c] } else { 0.0 }))
        .collect();
    write_floats(out, "Points", 3, &coordinates)?;
    writeln!(out, "</Points>\n<Cells>")?;
    let connectivity: Vec<i64> = cells
        .iter()
        .flat_map(|cell| cell_type.vtk_cell(cell).map(|n| n as i64))
        .collect();
    write_array(
        out,
        "Int64",
        "connectivity",
        1,
        &bytes_of(&connectivity, i64::to_le_bytes),
    )?;
    let offsets: Vec<i64> = (1..=cells.len() as i64).map(|c| N as i64 * c).collect();
    write_array(out, "Int64", "offsets", 1, &bytes_of(&offsets, i64::to_le_bytes))?;
    write_array(out, "UInt8", "types", 1, &vec![cell_type.vtk; cells.len()])?;
    writeln!(out, "</Cells>")?;
    for (tag, arrays) in [("PointData", point_data), ("CellData", cell_data)] {
        writeln!(out, "<{tag}>")?;
        for array in arrays {
            write_floats(out, &array.name, array.components, &array.values)?;
        }
        writeln!(out, "</{tag}>")?;
    }
    writeln!(out, "</Piece>\n</UnstructuredGrid>\n</VTKFile>")
}

/// The little-endian bytes of `values`.
fn bytes_of<T: Copy, const N: usize>(values: &[T], to_bytes: fn(T) -> [u8; N]) -> Vec<u8> {
    values.iter().flat_map(|&v| to_bytes(v)).collect()
}

/// One `Float64` data array.
fn write_floats(out: &mut impl Write, name: &str, components: usize, values: &[f64]) -> std::io::Result<()> {
    write_array(out, "Float64", name, components, &bytes_of(values, f64::to_le_bytes))
}

/// One data array in VTK's inline `binary` format: base64 of the `UInt64` length and the bytes.
fn write_array(out: &mut impl Write, kind: &str, name: &str, components: usize, bytes: &[u8]) -> std::io::Result<()> {
    use base64::Engine;
    let mut payload = Vec::with_capacity(8 + bytes.len());
    payload.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
    payload.extend_from_slice(bytes);
    writeln!(
        out,
        r#"<DataArray type="{kind}" Name="{name}" NumberOfComponents="{components}" format="binary">"#
    )?;
    writeln!(out, "{}", base64::engine::general_purpose::STANDARD.encode(&payload))?;
    writeln!(out, "</DataArray>")
}

/// A ParaView collection: `.vtu` files against `d`, rewritten after each addition so that an
/// interrupted run leaves a valid collection of what it wrote.
#[derive(Debug)]
pub struct Collection {
    path: PathBuf,
    entries: Vec<(f64, String)>,
}

impl Collection {
    /// An empty collection to be written at `path` (nothing is written until [`Collection::add`]).
    pub fn new(path: &Path) -> Self {
        Collection {
            path: path.to_path_buf(),
            entries: Vec::new(),
        }
    }

    /// The collection at `path` listing `entries` (`(d, file name)`, as
    /// [`Collection::entries`] gave them), rewritten.
    pub fn with_entries(path: &Path, entries: Vec<(f64, String)>) -> Result<Self> {
        let collection = Collection {
            path: path.to_path_buf(),
            entries,
        };
        collection.write()?;
        Ok(collection)
    }

    /// The files listed, `(d, file name)`.
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Adds `file` (a path in the collection's folder) at time `d` and rewrites the collection.
    pub fn add(&mut self, d: f64, file: &Path) -> Result<()> {
        let name = file
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        self.entries.push((d, name));
        self.write()
    }

    fn write(&self) -> Result<()> {
        let mut text = String::from(r#"<?xml version="1.0"?>"#);
        text.push_str("\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n");
        for (time, file) in &self.entries {
            text.push_str(&format!(
                "<DataSet timestep=\"{time}\" group=\"\" part=\"0\" file=\"{file}\"/>\n"
            ));
        }
        text.push_str("</Collection>\n</VTKFile>\n");
        super::atomic::write_file(&self.path, text)
    }

    /// Number of files listed.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no file is listed yet.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Where the collection is written.
    pub fn path(&self) -> &Path {
        &self.path
    }
}
