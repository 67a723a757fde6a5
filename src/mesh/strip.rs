//! The bilayer strip: 9-node biquadratic (Q2) quadrilaterals over the reference domain
//! `0 <= X <= L`, `-D <= Y <= 1` (`docs/model.md`, "The finite-element set-up"). Elements are
//! uniform in X (or refined near chosen points, [`XRefinement`]) and through the layer
//! `0 <= Y <= 1`; in the substrate they grow geometrically from `h0` at the interface,
//! `h_k = h0 r^k`, with `r` chosen so that `sum_k h_k = D` exactly.
//!
//! Only this generator knows the grid: nodes form a `(2 nx + 1) x (2 ny + 1)` grid numbered
//! column by column (Y fastest, the shorter direction), grid node `(i, j)` being
//! `i (2 ny + 1) + j`, with `i = 0` at `X = 0` and `j = 0` at `Y = -D`. Element nodes are in
//! tensor-product order: local node `a + 3 b` sits at `(xi, eta) = (a - 1, b - 1)`.

use super::{ElementKind, Face, Generator, Mesh, Region, BOTTOM, INTERFACE, LAYER_THICKNESS, LEFT, RIGHT, TOP};
use crate::error::{Error, Result};
use crate::numerics::density::equidistribute;
use crate::numerics::dofs::DofMap;
use crate::numerics::grading::geometric_ratio;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Size and grading of a structured bilayer mesh, and the element on it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MeshSpec {
    /// Number of elements along X.
    pub nx: usize,
    /// Number of elements through the layer (uniform unless [`MeshSpec::layer_grading`] > 1).
    pub layer_elements: usize,
    /// Ratio of consecutive layer elements, from the top surface down (1: uniform; above 1 the
    /// top element is the thinnest: the crease tip lies on the surface).
    pub layer_grading: f64,
    /// Number of (geometrically graded) elements through the substrate.
    pub substrate_elements: usize,
    /// Thickness `h0` of the top substrate element, at the interface `Y = 0`.
    pub top_substrate_thickness: f64,
    /// Half-length `L` of the domain.
    pub length: f64,
    /// Depth `D` of the substrate.
    pub depth: f64,
    /// Refinement in X (`None`: uniform).
    pub x_refinement: Option<XRefinement>,
    /// The element (default: mixed).
    pub element: ElementKind,
}

/// Elements in X sized inversely to the density `1 + (ratio - 1) sum_j exp(-((X - X_j) / width)^2)`
/// with centres `X_j = offset + j period` (e.g. the troughs of a seeded mode, or a crease at 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct XRefinement {
    /// How many times denser the elements are at a centre than far from all centres.
    pub ratio: f64,
    pub width: f64,
    pub offset: f64,
    pub period: f64,
}

impl XRefinement {
    /// The element density at `x`.
    pub fn density(&self, x: f64, length: f64) -> f64 {
        let first = ((-self.offset - 3.0 * self.width) / self.period).ceil() as i64;
        let last = ((length - self.offset + 3.0 * self.width) / self.period).floor() as i64;
        let bumps: f64 = (first..=last)
            .map(|j| (-((x - self.offset - j as f64 * self.period) / self.width).powi(2)).exp())
            .sum();
        1.0 + (self.ratio - 1.0) * bumps
    }

    fn validate(&self) -> Result<()> {
        if !(self.ratio.is_finite() && self.ratio >= 1.0) {
            return Err(Error::invalid("refinement ratio", self.ratio, "[1, inf)"));
        }
        for (name, value) in [("refinement width", self.width), ("refinement period", self.period)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(name, value, "(0, inf)"));
            }
        }
        Ok(())
    }
}

/// The three meshes of the half domain that runs are quoted on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum MeshPreset {
    /// [`MeshSpec::coarse`].
    #[default]
    #[value(help = "100 x (2 + 25) elements, h0 = 0.5: 22,110 unknowns")]
    Coarse,
    /// [`MeshSpec::fine`].
    #[value(help = "200 x (4 + 45) elements, h0 = 0.25: 79,398 unknowns")]
    Fine,
    /// [`MeshSpec::extra`].
    #[value(help = "400 x (8 + 90) elements, h0 = 0.125: 315,594 unknowns")]
    Extra,
}

impl MeshPreset {
    pub fn spec(self) -> MeshSpec {
        match self {
            MeshPreset::Coarse => MeshSpec::coarse(),
            MeshPreset::Fine => MeshSpec::fine(),
            MeshPreset::Extra => MeshSpec::extra(),
        }
    }
}

impl MeshSpec {
    /// Any mesh of the domain `[0, length] x [-depth, 1]`; validated by [`Mesh::new`].
    pub fn new(
        nx: usize,
        layer_elements: usize,
        substrate_elements: usize,
        top_substrate_thickness: f64,
        length: f64,
        depth: f64,
    ) -> Self {
        MeshSpec {
            nx,
            layer_elements,
            layer_grading: 1.0,
            substrate_elements,
            top_substrate_thickness,
            length,
            depth,
            x_refinement: None,
            element: ElementKind::default(),
        }
    }

    /// The same mesh with `element` on it.
    pub fn with_element(mut self, element: ElementKind) -> Self {
        self.element = element;
        self
    }

    /// The same mesh with its layer elements growing by `ratio` from the top surface down.
    pub fn with_layer_grading(mut self, ratio: f64) -> Self {
        self.layer_grading = ratio;
        self
    }

    /// Layer element thicknesses from the top surface down; they sum to the layer thickness.
    pub fn layer_thicknesses(&self) -> Vec<f64> {
        let (n, r) = (self.layer_elements, self.layer_grading);
        let top = match r == 1.0 {
            true => LAYER_THICKNESS / n as f64,
            false => LAYER_THICKNESS * (r - 1.0) / (r.powi(n as i32) - 1.0),
        };
        (0..n).map(|k| top * r.powi(k as i32)).collect()
    }

    /// The same mesh refined in X by `refinement`.
    pub fn refined(mut self, refinement: XRefinement) -> Self {
        self.x_refinement = Some(refinement);
        self
    }

    /// Width of the widest element column (in X).
    pub fn widest_column(&self) -> f64 {
        self.element_columns()
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(0.0, f64::max)
    }

    /// X of the element boundaries, from 0 to `L`.
    fn element_columns(&self) -> Vec<f64> {
        match self.x_refinement {
            None => (0..=self.nx).map(|i| self.length * i as f64 / self.nx as f64).collect(),
            Some(r) => equidistribute(|x| r.density(x, self.length), self.length, self.nx),
        }
    }

    /// The preset `coarse`, `fine` or `extra` by name.
    pub fn preset(name: &str) -> Result<Self> {
        match name {
            "coarse" => Ok(Self::coarse()),
            "fine" => Ok(Self::fine()),
            "extra" => Ok(Self::extra()),
            other => Err(Error::invalid("mesh", other, "coarse, fine or extra")),
        }
    }

    /// The same mesh with any of `nx`, the layer and substrate element counts and `h0` replaced.
    pub fn with_overrides(
        mut self,
        nx: Option<usize>,
        layer_elements: Option<usize>,
        substrate_elements: Option<usize>,
        h0: Option<f64>,
    ) -> Self {
        self.nx = nx.unwrap_or(self.nx);
        self.layer_elements = layer_elements.unwrap_or(self.layer_elements);
        self.substrate_elements = substrate_elements.unwrap_or(self.substrate_elements);
        self.top_substrate_thickness = h0.unwrap_or(self.top_substrate_thickness);
        self
    }

    /// The same mesh with the top substrate element `h0` set so that consecutive substrate
    /// elements grow by the ratio `r` in `[1, 2]`: `h0 (r^n - 1) / (r - 1) = D`.
    pub fn with_grading(mut self, r: f64) -> Result<Self> {
        if !(1.0..=2.0).contains(&r) {
            return Err(Error::invalid("grading", r, "[1, 2]"));
        }
        let n = self.substrate_elements as i32;
        self.top_substrate_thickness = if r == 1.0 {
            self.depth / n as f64
        } else {
            self.depth * (r - 1.0) / (r.powi(n) - 1.0)
        };
        Ok(self)
    }

    /// 100 / 2 / 25 elements, `h0 = 0.5` (bottom element about 5): 22,110 unknowns.
    pub fn coarse() -> Self {
        Self::new(100, 2, 25, 0.5, 50.0, 50.0)
    }

    /// 200 / 4 / 45 elements, `h0 = 0.25` (bottom element about 3): 79,398 unknowns.
    pub fn fine() -> Self {
        Self::new(200, 4, 45, 0.25, 50.0, 50.0)
    }

    /// 400 / 8 / 90 elements, `h0 = 0.125`: 315,594 unknowns.
    pub fn extra() -> Self {
        Self::new(400, 8, 90, 0.125, 50.0, 50.0)
    }

    /// Number of elements through the thickness, `layer_elements + substrate_elements`.
    pub fn ny(&self) -> usize {
        self.layer_elements + self.substrate_elements
    }

    /// Number of unknowns before boundary conditions, two per node.
    pub fn num_dofs(&self) -> usize {
        DofMap::PLANE.count((2 * self.nx + 1) * (2 * self.ny() + 1))
    }

    /// Checks counts and lengths; the grading needs `h0 < D` (or `h0 = D` for one element).
    pub fn validate(&self) -> Result<()> {
        for (name, count) in [
            ("mesh.nx", self.nx),
            ("mesh.layer_elements", self.layer_elements),
            ("mesh.substrate_elements", self.substrate_elements),
        ] {
            if count == 0 {
                return Err(Error::invalid(name, count, "an integer >= 1"));
            }
        }
        for (name, value) in [("mesh.length", self.length), ("mesh.depth", self.depth)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(name, value, "(0, inf)"));
            }
        }
        if let Some(r) = &self.x_refinement {
            r.validate()?;
        }
        if !(self.layer_grading.is_finite() && (1.0..=4.0).contains(&self.layer_grading)) {
            return Err(Error::invalid("mesh.layer_grading", self.layer_grading, "[1, 4]"));
        }
        let h0 = self.top_substrate_thickness;
        let feasible = if self.substrate_elements == 1 {
            (h0 - self.depth).abs() <= 1e-12 * self.depth
        } else {
            h0.is_finite() && h0 > 0.0 && h0 < self.depth
        };
        if feasible {
            Ok(())
        } else {
            let allowed = if self.substrate_elements == 1 {
                "= depth for one element"
            } else {
                "(0, depth)"
            };
            Err(Error::invalid("mesh.top_substrate_thickness", h0, allowed))
        }
    }

    /// Growth ratio `r` of the substrate elements, from `h0 (r^n - 1) / (r - 1) = D` (bisection).
    pub fn grading_ratio(&self) -> f64 {
        geometric_ratio(self.top_substrate_thickness, self.depth, self.substrate_elements)
    }

    /// Substrate element thicknesses from the interface down; they sum to `D` exactly.
    pub fn substrate_thicknesses(&self) -> Vec<f64> {
        let r = self.grading_ratio();
        let n = self.substrate_elements;
        let mut h: Vec<f64> = (0..n)
            .map(|k| self.top_substrate_thickness * r.powi(k as i32))
            .collect();
        // Absorb the bisection's round-off into the bottom element.
        h[n - 1] = self.depth - h[..n - 1].iter().sum::<f64>();
        h
    }

    /// Y of the element boundaries from the bottom `-D` to the top `1`.
    pub(super) fn element_rows(&self) -> Vec<f64> {
        let mut rows = vec![0.0];
        for h in self.substrate_thicknesses() {
            rows.push(rows.last().unwrap() - h);
        }
        *rows.last_mut().unwrap() = -self.depth;
        rows.reverse();
        let nl = self.layer_elements;
        if self.layer_grading == 1.0 {
            rows.extend((1..=nl).map(|k| LAYER_THICKNESS * k as f64 / nl as f64));
        } else {
            // Up from the interface, the thickest element first; the top lies at exactly 1.
            let mut y = 0.0;
            for h in self.layer_thicknesses().iter().rev().take(nl - 1) {
                y += h;
                rows.push(y);
            }
            rows.push(LAYER_THICKNESS);
        }
        rows
    }
}

impl Mesh {
    /// The perfect (unperturbed) mesh of `spec`.
    pub fn new(spec: MeshSpec) -> Result<Self> {
        spec.validate()?;
        let (columns, rows) = (2 * spec.nx + 1, 2 * spec.ny() + 1);
        let element_rows = spec.element_rows();
        let node_y: Vec<f64> = (0..rows)
            .map(|j| match j % 2 {
                0 => element_rows[j / 2],
                _ => 0.5 * (element_rows[j / 2] + element_rows[j / 2 + 1]),
            })
            .collect();
        let element_columns = spec.element_columns();
        let mut coordinates = Vec::with_capacity(columns * rows);
        for i in 0..columns {
            let x = match i % 2 {
                0 => element_columns[i / 2],
                _ => 0.5 * (element_columns[i / 2] + element_columns[i / 2 + 1]),
            };
            coordinates.extend(node_y.iter().map(|&y| [x, y]));
        }
        let mut elements = Vec::with_capacity(spec.nx * spec.ny());
        let mut regions = Vec::with_capacity(spec.nx * spec.ny());
        for ex in 0..spec.nx {
            for ey in 0..spec.ny() {
                elements.push(std::array::from_fn(|local| {
                    (2 * ex + local % 3) * rows + 2 * ey + local / 3
                }));
                regions.push(if ey < spec.substrate_elements {
                    Region::Substrate
                } else {
                    Region::Layer
                });
            }
        }
        let grid = |i: usize, j: usize| i * rows + j;
        let node_sets = BTreeMap::from([
            (LEFT, (0..rows).map(|j| grid(0, j)).collect()),
            (RIGHT, (0..rows).map(|j| grid(columns - 1, j)).collect()),
            (BOTTOM, (0..columns).map(|i| grid(i, 0)).collect()),
            (TOP, (0..columns).map(|i| grid(i, rows - 1)).collect()),
            (
                INTERFACE,
                (0..columns).map(|i| grid(i, 2 * spec.substrate_elements)).collect(),
            ),
        ]);
        // The top edge of each top element: its local nodes 6, 7, 8 (eta = 1), by increasing X.
        let top_faces = (0..spec.nx)
            .map(|ex| {
                let element = ex * spec.ny() + spec.ny() - 1;
                let nodes = [6, 7, 8].iter().map(|&local| elements[element][local]).collect();
                Face { element, nodes }
            })
            .collect();
        let face_sets = BTreeMap::from([(TOP, top_faces)]);
        Ok(Mesh {
            generator: Generator::Strip(spec),
            element: spec.element,
            coordinates,
            elements,
            regions,
            node_sets,
            face_sets,
            periods: [0.0; 2],
            wraps: Vec::new(),
        })
    }

    /// The specification the mesh was built from.
    pub fn spec(&self) -> &MeshSpec {
        match &self.generator {
            Generator::Strip(spec) => spec,
            Generator::Patch(_) => unreachable!("plane meshes are strips"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grading_ratio_sets_the_top_substrate_element_that_gives_it_back() {
        for r in [1.0, 1.05, 1.2, 2.0] {
            let spec = MeshSpec::coarse().with_grading(r).unwrap();
            assert!((spec.grading_ratio() - r).abs() < 1e-9, "{r}: {}", spec.grading_ratio());
        }
        let message = MeshSpec::coarse().with_grading(2.5).unwrap_err().to_string();
        assert!(message.contains("`grading`") && message.contains("[1, 2]"), "{message}");
    }

    #[test]
    fn small_mesh_numbering_and_sets() {
        let mesh = Mesh::new(MeshSpec::new(2, 1, 2, 2.0, 4.0, 5.0)).unwrap();
        // A 5 x 7 grid of nodes, numbered column by column.
        let node = |i: usize, j: usize| 7 * i + j;
        assert_eq!(mesh.num_nodes(), 35);
        assert_eq!(mesh.elements().len(), 6);
        // First element: bottom-left corner at node 0, centre at grid (1, 1).
        assert_eq!(mesh.elements()[0][0], 0);
        assert_eq!(mesh.elements()[0][4], node(1, 1));
        assert_eq!(mesh.elements()[0][8], node(2, 2));
        assert_eq!(
            mesh.node_set_names().collect::<Vec<_>>(),
            [BOTTOM, INTERFACE, LEFT, RIGHT, TOP]
        );
        assert_eq!(mesh.left(), (0..7).collect::<Vec<_>>());
        // The top faces: two edges whose nodes run along the top node set.
        let faces = mesh.face_set(TOP);
        assert_eq!(faces.iter().map(|f| f.element).collect::<Vec<_>>(), [2, 5]);
        assert_eq!(
            faces.iter().flat_map(|f| f.nodes.clone()).collect::<Vec<_>>(),
            [6, 13, 20, 20, 27, 34]
        );
        assert_eq!(mesh.top(), [6, 13, 20, 27, 34]);
        assert_eq!(mesh.right(), (28..35).collect::<Vec<_>>());
        assert_eq!(mesh.regions()[2], Region::Layer);
        assert_eq!(mesh.coordinates()[mesh.top()[4]], [4.0, 1.0]);
        assert_eq!(mesh.coordinates()[mesh.bottom()[0]], [0.0, -5.0]);
        assert_eq!(mesh.coordinates()[mesh.interface()[2]][1], 0.0);
        assert_eq!(mesh.coordinates()[node(0, 1)][1], -3.5);
        assert_eq!(mesh.spec().substrate_thicknesses(), vec![2.0, 3.0]);
    }

    #[test]
    fn invalid_specs_are_rejected() {
        assert!(Mesh::new(MeshSpec::new(0, 1, 1, 5.0, 4.0, 5.0)).is_err());
        assert!(Mesh::new(MeshSpec::new(1, 1, 3, 6.0, 4.0, 5.0)).is_err());
        assert!(Mesh::new(MeshSpec::new(1, 1, 1, 2.0, 4.0, 5.0)).is_err());
        assert!(Mesh::new(MeshSpec::new(1, 1, 1, 5.0, 4.0, 5.0)).is_ok());
    }
}
