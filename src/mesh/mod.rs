//! Meshes of the bilayer. A [`Mesh`] is nodes, cells of quadratic Lagrange elements (the 9-node
//! quadrilateral in two dimensions, the 27-node hexahedron in three), a region per cell, named
//! node sets ([`LEFT`], [`RIGHT`], [`BOTTOM`], [`TOP`], [`INTERFACE`], and in three dimensions
//! [`BACK`], [`FRONT`]) and named face sets ([`TOP`]): what boundary conditions, contact
//! surfaces and probes address. Two generators make them and only they know their grids: the
//! plane strip of the paper ([`strip`], [`MeshSpec`]) and the three-dimensional patch of tissue
//! ([`patch`], [`PatchSpec`]). The unknowns are numbered by the mesh's [`DofMap`].
//!
//! A mesh may be periodic along some directions: an element on the far side of the period then
//! shares its nodes with the near side, and its own reference coordinates are those of the
//! nodes shifted by the period ([`Mesh::element_coordinates`]).

mod element_kind;
pub mod patch;
pub mod strip;

pub use crate::numerics::dofs::{DofMap, X, Y, Z};
pub use element_kind::ElementKind;
pub use patch::{PatchSpec, Sides};
use std::collections::BTreeMap;
pub use strip::{MeshPreset, MeshSpec, XRefinement};

/// The left side `X = 0`, bottom to top.
pub const LEFT: &str = "left";
/// The right side `X = L`, bottom to top.
pub const RIGHT: &str = "right";
/// The back side `Z = 0` of a three-dimensional mesh.
pub const BACK: &str = "back";
/// The front side `Z = Lz` of a three-dimensional mesh.
pub const FRONT: &str = "front";
/// The bottom `Y = -D`, by increasing X.
pub const BOTTOM: &str = "bottom";
/// The top surface `Y = 1`, by increasing X.
pub const TOP: &str = "top";
/// The interface `Y = 0` of the layer and the substrate, by increasing X.
pub const INTERFACE: &str = "interface";

/// Thickness of the stiff layer: the unit of length.
pub const LAYER_THICKNESS: f64 = 1.0;

/// Which tissue an element belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// The stiff layer, `0 <= Y <= 1`.
    Layer,
    /// The fibre-reinforced substrate, `-D <= Y <= 0`.
    Substrate,
}

/// What generated a mesh, with its specification.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Generator {
    Strip(MeshSpec),
    Patch(PatchSpec),
}

/// A mesh of quadratic elements in `D` dimensions with `N` nodes each: reference node
/// coordinates, element connectivity, regions and named node and face sets.
#[derive(Clone, Debug)]
pub struct Mesh<const D: usize = 2, const N: usize = 9> {
    generator: Generator,
    element: ElementKind,
    coordinates: Vec<[f64; D]>,
    elements: Vec<[usize; N]>,
    regions: Vec<Region>,
    node_sets: BTreeMap<&'static str, Vec<usize>>,
    face_sets: BTreeMap<&'static str, Vec<Face>>,
    /// The period along each direction (zero where the mesh is not periodic).
    periods: [f64; D],
    /// For each element of a periodic mesh, each local node's shifts: bit `c` set when the
    /// element sees the node one period further along direction `c` (empty when not periodic).
    wraps: Vec<[u8; N]>,
}

/// One face of an element on a boundary (an edge in two dimensions): the element and the
/// face's nodes, in the order of the boundary's node set.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Face {
    pub element: usize,
    pub nodes: Vec<usize>,
}

impl<const D: usize, const N: usize> Mesh<D, N> {
    /// Moves every node `X` to `X + displacement(X)` (an imperfection of the reference geometry);
    /// node sets and regions stay.
    pub fn perturbed(mut self, displacement: impl Fn([f64; D]) -> [f64; D]) -> Self {
        for x in &mut self.coordinates {
            let dx = displacement(*x);
            *x = std::array::from_fn(|c| x[c] + dx[c]);
        }
        self
    }

    /// The finite element the cells carry.
    pub fn element(&self) -> ElementKind {
        self.element
    }

    /// Reference coordinates of every node.
    pub fn coordinates(&self) -> &[[f64; D]] {
        &self.coordinates
    }

    /// The nodes of every element (tensor-product order: local node `a + 3 b (+ 9 c)` at
    /// `(xi, eta, zeta) = (a - 1, b - 1, c - 1)`).
    pub fn elements(&self) -> &[[usize; N]] {
        &self.elements
    }

    /// The reference coordinates of element `e`'s nodes, as the element sees them (across a
    /// periodic side, one period on).
    pub fn element_coordinates(&self, e: usize) -> [[f64; D]; N] {
        let nodes = &self.elements[e];
        std::array::from_fn(|a| {
            let x = self.coordinates[nodes[a]];
            match self.wraps.get(e) {
                None => x,
                Some(wraps) => std::array::from_fn(|c| match wraps[a] >> c & 1 {
                    1 => x[c] + self.periods[c],
                    _ => x[c],
                }),
            }
        })
    }

    /// The mesh cut open along its periodic sides, for drawing: the nodes, then one copy of
    /// each node an element sees one period on (at its shifted coordinates); the elements on
    /// those points; and for every point the mesh node it copies.
    pub fn unwrapped(&self) -> (Vec<[f64; D]>, Vec<[usize; N]>, Vec<usize>) {
        let mut points = self.coordinates.clone();
        let mut source: Vec<usize> = (0..self.num_nodes()).collect();
        let mut copies: BTreeMap<(usize, u8), usize> = BTreeMap::new();
        let cells = (0..self.elements.len())
            .map(|e| {
                let shifted = self.element_coordinates(e);
                std::array::from_fn(|a| {
                    let node = self.elements[e][a];
                    match self.wraps.get(e).map_or(0, |w| w[a]) {
                        0 => node,
                        wrap => *copies.entry((node, wrap)).or_insert_with(|| {
                            points.push(shifted[a]);
                            source.push(node);
                            points.len() - 1
                        }),
                    }
                })
            })
            .collect();
        (points, cells, source)
    }

    /// Whether the mesh is periodic along some direction.
    pub fn is_periodic(&self) -> bool {
        !self.wraps.is_empty()
    }

    /// The period along each direction (zero where the mesh is not periodic).
    pub fn periods(&self) -> &[f64; D] {
        &self.periods
    }

    /// The region of every element.
    pub fn regions(&self) -> &[Region] {
        &self.regions
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.coordinates.len()
    }

    /// How the mesh's unknowns are numbered: `D` displacement components per node.
    pub fn dofs(&self) -> DofMap {
        DofMap::of_dimension(D)
    }

    /// Number of unknowns, `D` per node.
    pub fn num_dofs(&self) -> usize {
        self.dofs().count(self.num_nodes())
    }

    /// The nodes of the set called `name` ([`LEFT`], [`RIGHT`], [`BOTTOM`], [`TOP`],
    /// [`INTERFACE`], ...), in the set's order. A name the mesh has no set of is a bug (panic).
    pub fn node_set(&self, name: &str) -> &[usize] {
        self.node_sets
            .get(name)
            .unwrap_or_else(|| panic!("the mesh has no node set `{name}`"))
    }

    /// Whether the mesh has a node set called `name`.
    pub fn has_node_set(&self, name: &str) -> bool {
        self.node_sets.contains_key(name)
    }

    /// The faces of the set called `name` ([`TOP`]), in the set's order. A name the mesh has no
    /// face set of is a bug (panic).
    pub fn face_set(&self, name: &str) -> &[Face] {
        self.face_sets
            .get(name)
            .unwrap_or_else(|| panic!("the mesh has no face set `{name}`"))
    }

    /// The names of the node sets.
    pub fn node_set_names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.node_sets.keys().copied()
    }

    /// Nodes on the left side `X = 0`, bottom to top (the set [`LEFT`]).
    pub fn left(&self) -> Vec<usize> {
        self.node_set(LEFT).to_vec()
    }

    /// Nodes on the right side `X = L`, bottom to top (the set [`RIGHT`]).
    pub fn right(&self) -> Vec<usize> {
        self.node_set(RIGHT).to_vec()
    }

    /// Nodes on the bottom `Y = -D`, sorted by X (the set [`BOTTOM`]).
    pub fn bottom(&self) -> Vec<usize> {
        self.node_set(BOTTOM).to_vec()
    }

    /// Nodes on the top surface `Y = 1`, sorted by X (the set [`TOP`]).
    pub fn top(&self) -> Vec<usize> {
        self.node_set(TOP).to_vec()
    }

    /// Nodes on the interface `Y = 0`, sorted by X (the set [`INTERFACE`]).
    pub fn interface(&self) -> Vec<usize> {
        self.node_set(INTERFACE).to_vec()
    }
}
