//! Global assembly of the nonlinear system on the free unknowns.
//!
//! Prescribed unknowns are eliminated: the residual `r_f = f_int,f(u)` and the tangent
//! `K_ff = d r_f / d u_f` live on the free unknowns only, which keeps `K_ff` symmetric (and
//! positive definite wherever the equilibrium is stable). The CSC pattern of `K_ff` (both
//! triangles) and its `Argsort` are built once per set of prescribed unknowns; each assembly
//! computes the element matrices in parallel (rayon) straight into their own slices of the
//! value array, which `SparseColMat::new_from_argsort` then sums into the matrix.

use super::boundary::Dirichlet;
use super::element::{self, ElementGeometry, ElementState, ElementVector, DOFS};
use crate::error::{Error, Result};
use crate::material::{Bilayer, Tissue};
use crate::mesh::{Mesh, Region};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Source of pattern identifiers, unique across systems.
static NEXT_PATTERN: AtomicUsize = AtomicUsize::new(0);

/// Where a global unknown goes in the reduced system.
#[derive(Clone, Copy, Debug)]
enum Slot {
    /// Index among the free unknowns.
    Free(usize),
    /// Index among the prescribed unknowns.
    Fixed(usize),
}

/// The reduced system's sparsity for one set of prescribed unknowns.
struct Pattern {
    id: usize,
    constrained: Vec<usize>,
    slots: Vec<Slot>,
    free: Vec<usize>,
    /// Element `e` owns `values[offsets[e]..offsets[e + 1]]`: its free-free block, row-major.
    offsets: Vec<usize>,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
}

/// The assembled nonlinear system at one displacement.
#[derive(Debug)]
pub struct Assembled {
    /// Residual on the free unknowns: internal force, plus `K_fc du_c` when lifted.
    pub residual: Vec<f64>,
    /// Tangent `K_ff` (both triangles), when requested.
    pub tangent: Option<SparseColMat<usize, f64>>,
    /// Internal force on each prescribed unknown (the reaction), in the order of `Dirichlet::dofs`.
    pub reactions: Vec<f64>,
    /// Total strain energy.
    pub energy: f64,
    /// Smallest `J = det F` over all Gauss points.
    pub min_jacobian: f64,
    /// Identifies the sparsity pattern (changes when the prescribed set does).
    pub pattern: usize,
    /// Wall time of this assembly.
    pub elapsed: Duration,
}

impl Assembled {
    /// Euclidean norm of the free residual.
    pub fn residual_norm(&self) -> f64 {
        norm(&self.residual)
    }

    /// Norm of the internal force on all unknowns (free residual and reactions): a force scale.
    pub fn force_norm(&self) -> f64 {
        self.residual_norm().hypot(norm(&self.reactions))
    }
}

/// Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A mesh with its materials and element geometry, ready to assemble.
pub struct System {
    mesh: Mesh,
    materials: Vec<Tissue>,
    geometry: Vec<ElementGeometry>,
    pattern: Option<Pattern>,
}

impl System {
    /// The layer's material in layer elements, the substrate's in substrate elements.
    pub fn new(mesh: Mesh, materials: &Bilayer) -> Result<Self> {
        let tissues = mesh
            .regions()
            .iter()
            .map(|region| match region {
                Region::Layer => materials.layer_tissue(),
                Region::Substrate => materials.substrate_tissue(),
            })
            .collect();
        let coordinates = mesh.coordinates();
        let geometry = mesh
            .elements()
            .iter()
            .map(|nodes| ElementGeometry::new(&nodes.map(|n| coordinates[n])))
            .collect::<Result<_>>()?;
        Ok(System {
            mesh,
            materials: tissues,
            geometry,
            pattern: None,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The material of every element.
    pub fn materials(&self) -> &[Tissue] {
        &self.materials
    }

    /// The reference geometry of every element.
    pub fn geometry(&self) -> &[ElementGeometry] {
        &self.geometry
    }

    /// Number of unknowns before boundary conditions.
    pub fn num_dofs(&self) -> usize {
        self.mesh.num_dofs()
    }

    /// Nodal displacements of element `e` from the global vector `u`.
    pub fn element_displacements(&self, e: usize, u: &[f64]) -> ElementVector {
        let nodes = &self.mesh.elements()[e];
        std::array::from_fn(|i| u[2 * nodes[i / 2] + i % 2])
    }

    /// The free unknowns when `bc` is prescribed, increasing; position = index in the reduced system.
    pub fn free_dofs(&mut self, bc: &Dirichlet) -> Result<&[usize]> {
        Ok(&self.pattern_for(bc)?.free)
    }

    /// Residual (and tangent if `with_tangent`) on the free unknowns at the full displacement `u`.
    ///
    /// `lift`, one value per prescribed unknown, adds `K_fc lift` to the residual: the linearised
    /// effect of moving the prescribed unknowns by `lift` (the first Newton step of a load step).
    /// Panics if `u` or `lift` have the wrong length. `J <= 0` anywhere is an error.
    pub fn assemble(
        &mut self,
        u: &[f64],
        bc: &Dirichlet,
        lift: Option<&[f64]>,
        with_tangent: bool,
    ) -> Result<Assembled> {
        assert_eq!(u.len(), self.num_dofs(), "displacement vector length");
        assert!(
            lift.is_none_or(|l| l.len() == bc.len()),
            "one lift value per prescribed unknown"
        );
        let start = Instant::now();
        self.pattern_for(bc)?;
        let pattern = self.pattern.as_ref().expect("built above");
        let total = if with_tangent {
            *pattern.offsets.last().unwrap_or(&0)
        } else {
            0
        };
        let mut values = vec![0.0; total];
        let chunks = split(&mut values, &pattern.offsets, with_tangent);
        let results = chunks
            .into_par_iter()
            .enumerate()
            .with_min_len(32)
            .map(|(e, chunk)| self.element_contribution(pattern, e, u, lift, chunk))
            .collect::<Result<Vec<_>>>()?;

        let mut residual = vec![0.0; pattern.free.len()];
        let mut reactions = vec![0.0; bc.len()];
        let (mut energy, mut min_jacobian) = (0.0, f64::INFINITY);
        for (nodes, (state, lifted)) in self.mesh.elements().iter().zip(&results) {
            for i in 0..DOFS {
                match pattern.slots[2 * nodes[i / 2] + i % 2] {
                    Slot::Free(f) => residual[f] += state.force[i] + lifted[i],
                    Slot::Fixed(c) => reactions[c] += state.force[i],
                }
            }
            energy += state.energy;
            min_jacobian = min_jacobian.min(state.min_jacobian);
        }
        let tangent = with_tangent.then(|| {
            SparseColMat::new_from_argsort(pattern.symbolic.clone(), &pattern.argsort, &values)
                .expect("allocating the tangent's values")
        });
        Ok(Assembled {
            residual,
            tangent,
            reactions,
            energy,
            min_jacobian,
            pattern: pattern.id,
            elapsed: start.elapsed(),
        })
    }

    /// Element `e`'s state, its lifting force `K_e lift_e`, and its free-free block into `chunk`.
    fn element_contribution(
        &self,
        pattern: &Pattern,
        e: usize,
        u: &[f64],
        lift: Option<&[f64]>,
        chunk: &mut [f64],
    ) -> Result<(ElementState, ElementVector)> {
        let nodes = &self.mesh.elements()[e];
        let slots: [Slot; DOFS] = std::array::from_fn(|i| pattern.slots[2 * nodes[i / 2] + i % 2]);
        let needs_tangent = !chunk.is_empty() || lift.is_some();
        let mut k = [[0.0; DOFS]; DOFS];
        let state = element::evaluate(
            &self.geometry[e],
            &self.materials[e],
            &self.element_displacements(e, u),
            needs_tangent.then_some(&mut k),
        )?;
        let mut lifted = [0.0; DOFS];
        if let Some(lift) = lift {
            for (b, slot) in slots.iter().enumerate() {
                if let Slot::Fixed(c) = *slot {
                    for (a, l) in lifted.iter_mut().enumerate() {
                        *l += k[a][b] * lift[c];
                    }
                }
            }
        }
        if !chunk.is_empty() {
            let free = || slots.iter().enumerate().filter(|(_, s)| matches!(s, Slot::Free(_)));
            let mut entries = chunk.iter_mut();
            for (a, _) in free() {
                for (b, _) in free() {
                    *entries.next().expect("chunk sized by the pattern") = k[a][b];
                }
            }
        }
        Ok((state, lifted))
    }

    /// The cached pattern for `bc`'s prescribed unknowns, rebuilt when they change.
    fn pattern_for(&mut self, bc: &Dirichlet) -> Result<&Pattern> {
        let n = self.num_dofs();
        if let Some(&bad) = bc.dofs().iter().find(|&&d| d >= n) {
            return Err(Error::invalid("prescribed unknown", bad, &format!("[0, {n})")));
        }
        if self.pattern.as_ref().is_none_or(|p| p.constrained != bc.dofs()) {
            let id = NEXT_PATTERN.fetch_add(1, Ordering::Relaxed);
            self.pattern = Some(build_pattern(&self.mesh, bc.dofs(), id));
        }
        Ok(self.pattern.as_ref().expect("just built"))
    }
}

/// Slots, free list, per-element offsets and the CSC pattern of `K_ff`.
fn build_pattern(mesh: &Mesh, constrained: &[usize], id: usize) -> Pattern {
    let mut slots = vec![Slot::Free(0); mesh.num_dofs()];
    for (c, &dof) in constrained.iter().enumerate() {
        slots[dof] = Slot::Fixed(c);
    }
    let mut free = Vec::with_capacity(slots.len() - constrained.len());
    for (dof, slot) in slots.iter_mut().enumerate() {
        if let Slot::Free(f) = slot {
            *f = free.len();
            free.push(dof);
        }
    }
    let mut offsets = vec![0];
    let mut pairs = Vec::new();
    for nodes in mesh.elements() {
        let local: Vec<usize> = (0..DOFS)
            .filter_map(|i| match slots[2 * nodes[i / 2] + i % 2] {
                Slot::Free(f) => Some(f),
                Slot::Fixed(_) => None,
            })
            .collect();
        for &row in &local {
            pairs.extend(local.iter().map(|&col| Pair::new(row, col)));
        }
        offsets.push(pairs.len());
    }
    let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(free.len(), free.len(), &pairs)
        .expect("pattern indices are in range by construction");
    Pattern {
        id,
        constrained: constrained.to_vec(),
        slots,
        free,
        offsets,
        symbolic,
        argsort,
    }
}

/// One mutable slice of `values` per element (empty ones when no tangent is assembled).
fn split<'a>(values: &'a mut [f64], offsets: &[usize], with_tangent: bool) -> Vec<&'a mut [f64]> {
    let elements = offsets.len() - 1;
    if !with_tangent {
        return (0..elements).map(|_| <&mut [f64]>::default()).collect();
    }
    let mut rest = values;
    offsets
        .windows(2)
        .map(|w| {
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(w[1] - w[0]);
            rest = tail;
            head
        })
        .collect()
}
