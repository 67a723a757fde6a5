//! Global assembly of the nonlinear system on the free unknowns.
//!
//! Prescribed unknowns are eliminated: the residual `r_f = f_int,f(u)` and the tangent
//! `K_ff = d r_f / d u_f` live on the free unknowns only, which keeps `K_ff` symmetric (and
//! positive definite wherever the equilibrium is stable). Only its lower triangle is stored
//! (the factorisation and [`crate::fem::linear_solver::multiply`] read that one). The CSC
//! pattern of that triangle and, for every stored entry, the list of element-matrix entries that sum into it
//! are built once per set of prescribed unknowns; each assembly computes the element matrices
//! in parallel (rayon) straight into their own slices of a reused buffer, and then sums each
//! stored entry from that list, in parallel too (no scatter, so no races and no sorting).
//! Groups of an [`AddedEnergy`] (contact pairs) are assembled like extra elements and added into
//! their stored entries (`pattern`): a change of the groups re-analyses the factorisation only
//! when a group couples unknowns that no stored entry coupled before.

use super::added::{AddedEnergy, Block, NoAddedEnergy};
use super::boundary::Dirichlet;
use super::element::{
    pressures, ElementGeometry, ElementMatrix, ElementState, ElementVector, FiniteElement, Penalty, Pressures,
    Registry, DOFS, GAUSS_POINTS, NODES,
};
use crate::error::{Error, Result};
use crate::material::{Bilayer, Tissue};
use crate::mesh::{ElementKind, Mesh, Region};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::{Duration, Instant};

mod multipliers;
mod pattern;
mod tangent;

pub use tangent::Tangent;

pub use pattern::StoredEntries;
use pattern::{Pattern, Slot};

/// The assembled nonlinear system at one displacement.
#[derive(Debug)]
pub struct Assembled {
    /// Residual on the free unknowns: internal force, plus `K_fc du_c` when lifted.
    pub residual: Vec<f64>,
    /// Tangent `K_ff` (lower triangle), when requested.
    pub tangent: Option<Tangent>,
    /// Internal force on each prescribed unknown (the reaction), in the order of `Dirichlet::dofs`.
    pub reactions: Vec<f64>,
    /// Total strain energy.
    pub energy: f64,
    /// The potential whose gradient the residual is (without the added terms): `energy`,
    /// except where the mixed element's multipliers are held fixed ([`crate::fem::element::mixed`]).
    pub potential: f64,
    /// Energy of the added terms (zero without them).
    pub added_energy: f64,
    /// Smallest `J = det F` over all Gauss points.
    pub min_jacobian: f64,
    /// Identifies the layout of the assembly (changes when the prescribed set or the added
    /// groups do).
    pub pattern: usize,
    /// Identifies the stored entries of the tangent (changes only when a prescribed set or a
    /// group needs entries not stored before): matrices with one structure share a symbolic
    /// factorisation.
    pub structure: usize,
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

/// A mesh with its materials and element geometry, ready to assemble: in `D` dimensions, of
/// elements with `N` nodes, `Q` quadrature points and `U = D N` unknowns (by default the plane
/// strip's; [`PatchSystem`] is the three-dimensional patch's).
pub struct System<const D: usize = 2, const N: usize = NODES, const Q: usize = GAUSS_POINTS, const U: usize = DOFS> {
    mesh: Mesh<D, N>,
    /// The tissues at no load, which a growth load grows.
    unloaded: Bilayer,
    /// The load's strain `d` the tissues are at.
    load: f64,
    /// The load's strain `d_3` along `Z` (zero in plane strain).
    load3: f64,
    materials: Vec<Tissue>,
    geometry: Vec<ElementGeometry<D, N, Q>>,
    /// The finite element of every element, of the kind the mesh names.
    elements: Vec<Box<dyn FiniteElement<D, N, Q, U>>>,
    /// The average displacement gradient carried across a periodic mesh's sides: an element
    /// of it sees the nodal displacements `u_a + H X_a` (zero, and unused, on other meshes).
    average_gradient: [[f64; D]; D],
    /// Whether some element resists volume change through multipliers (incompressible tissue,
    /// or a bulk modulus far above the shear modulus): the unknowns' vector then ends with
    /// [`pressures`]`(D)` multipliers per element ([`crate::fem::element::mixed`]).
    multipliers: bool,
    pattern: Option<Pattern>,
    /// Element-matrix entries of the last assembly (reused to avoid reallocating).
    entries: Vec<f64>,
}

/// The system of a three-dimensional patch of 27-node hexahedra.
pub type PatchSystem = System<3, 27, 27, 81>;

impl System {
    /// The layer's material in layer elements, the substrate's in substrate elements, with the
    /// element the mesh names. Incompressible tissue needs the mixed element.
    pub fn new(mesh: Mesh, materials: &Bilayer) -> Result<Self> {
        Self::build(mesh, materials)
    }
}

impl PatchSystem {
    /// [`System::new`] on a patch.
    pub fn on_patch(mesh: Mesh<3, 27>, materials: &Bilayer) -> Result<Self> {
        Self::build(mesh, materials)
    }
}

impl<const D: usize, const N: usize, const Q: usize, const U: usize> System<D, N, Q, U>
where
    ElementKind: Registry<D, N, Q, U>,
{
    fn build(mesh: Mesh<D, N>, materials: &Bilayer) -> Result<Self> {
        mesh.element().check_for(materials.incompressible)?;
        <ElementKind as Registry<D, N, Q, U>>::check_available(mesh.element())?;
        let geometry = (0..mesh.elements().len())
            .map(|e| {
                ElementGeometry::new::<<ElementKind as Registry<D, N, Q, U>>::Reference>(&mesh.element_coordinates(e))
            })
            .collect::<Result<Vec<_>>>()?;
        let mut system = System {
            mesh,
            unloaded: *materials,
            load: 0.0,
            load3: 0.0,
            materials: Vec::new(),
            geometry,
            elements: Vec::new(),
            average_gradient: [[0.0; D]; D],
            multipliers: false,
            pattern: None,
            entries: Vec::new(),
        };
        system.set_materials(materials);
        Ok(system)
    }

    /// Gives every element its tissue from `materials`, in an element of the mesh's kind.
    fn set_materials(&mut self, materials: &Bilayer) {
        self.materials = self
            .mesh
            .regions()
            .iter()
            .map(|region| match region {
                Region::Layer => materials.layer_tissue(),
                Region::Substrate => materials.substrate_tissue(),
            })
            .collect();
        let kind = self.mesh.element();
        self.elements = self
            .geometry
            .iter()
            .zip(&self.materials)
            .map(|(g, t)| kind.element(g, t, multipliers::augmentation(materials, t)))
            .collect();
        self.multipliers = self.elements.iter().any(|element| element.has_multipliers());
    }

    /// Puts the tissues at the load's strain `d`: under growth they grow to `g = 1/(1 - d)`
    /// (under compression they stay). The boundary conditions are the load path's.
    pub fn set_load(&mut self, d: f64) {
        self.set_biaxial_load(d, 0.0);
    }

    /// Puts the tissues at the load's strains `d` along `X` and `d_3` along `Z`: under growth
    /// they grow to `g = 1/(1 - d)` and `g3 = 1/(1 - d_3)` ([`Bilayer::at_biaxial_load`]).
    pub fn set_biaxial_load(&mut self, d: f64, d3: f64) {
        if self.unloaded.load.is_growth() && (d, d3) != (self.load, self.load3) {
            let (materials, _) = self.unloaded.at_biaxial_load(d, d3);
            self.set_materials(&materials);
        }
        (self.load, self.load3) = (d, d3);
    }

    /// The load's strain `d` the system is at.
    pub fn load(&self) -> f64 {
        self.load
    }

    /// The tissues at no load.
    pub fn unloaded_materials(&self) -> &Bilayer {
        &self.unloaded
    }

    /// The system of the same elements on `mesh`, whose nodes have moved (an imperfect
    /// geometry): like [`System::new`], but keeping the sparsity pattern and its identity, so
    /// that a factorisation's analysis carries over. `mesh` must have the same elements.
    pub fn with_moved_nodes(self, mesh: Mesh<D, N>, materials: &Bilayer) -> Result<Self> {
        assert_eq!(mesh.elements(), self.mesh.elements(), "the same elements");
        let mut moved = Self::build(mesh, materials)?;
        moved.average_gradient = self.average_gradient;
        moved.set_biaxial_load(self.load, self.load3);
        moved.pattern = self.pattern;
        Ok(moved)
    }

    /// What rebuilds the current sparsity pattern with the same stored entries, if one is built.
    pub fn stored_entries(&self) -> Option<StoredEntries> {
        self.pattern.as_ref().map(Pattern::stored_entries)
    }

    /// The sparsity pattern rebuilt from `entries` ([`System::stored_entries`] of this system
    /// at an earlier state), or none.
    pub fn recall_stored_entries(&mut self, entries: Option<StoredEntries>) -> Result<()> {
        self.pattern =
            match entries {
                Some(entries) => Some(Pattern::rebuilt(&self.mesh, entries).ok_or_else(|| {
                    Error::invalid("checkpoint", "its sparsity pattern", "one of this run's unknowns")
                })?),
                None => None,
            };
        Ok(())
    }

    /// Whether an assembly with `bc` prescribed and `groups` added keeps the current stored
    /// entries (so a factorisation needs no new analysis).
    pub fn keeps_structure(&self, bc: &Dirichlet, groups: &[Vec<usize>]) -> bool {
        self.pattern.as_ref().is_some_and(|p| p.fits(bc.dofs(), groups))
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh<D, N> {
        &self.mesh
    }

    /// The material of every element.
    pub fn materials(&self) -> &[Tissue] {
        &self.materials
    }

    /// The reference geometry of every element.
    pub fn geometry(&self) -> &[ElementGeometry<D, N, Q>] {
        &self.geometry
    }

    /// The finite element of every element.
    pub fn elements(&self) -> &[Box<dyn FiniteElement<D, N, Q, U>>] {
        &self.elements
    }

    /// Element `e`'s force, energy and smallest `J` at its nodal displacements `u` (and
    /// multipliers `lambda`, used by incompressible elements only, whose constraint is
    /// penalised as `penalty` says), and its tangent into `stiffness` when given, by the
    /// mesh's element.
    pub fn element_state(
        &self,
        e: usize,
        u: &ElementVector<U>,
        lambda: &Pressures,
        penalty: Penalty,
        stiffness: Option<&mut ElementMatrix<U>>,
    ) -> Result<ElementState<U>> {
        self.elements[e].evaluate(&self.geometry[e], u, lambda, penalty, stiffness)
    }

    /// Number of unknowns: the displacements of every node, then, for incompressible tissue,
    /// the multipliers of every element.
    pub fn num_dofs(&self) -> usize {
        self.mesh.num_dofs()
            + if self.multipliers {
                pressures(D) * self.elements.len()
            } else {
                0
            }
    }

    /// Nodal displacements of element `e` from the global vector `u`: on a periodic mesh the
    /// periodic part `u` plus the average part `H X` at the element's own nodes.
    pub fn element_displacements(&self, e: usize, u: &[f64]) -> ElementVector<U> {
        let (dofs, nodes) = (self.mesh.dofs(), &self.mesh.elements()[e]);
        let periodic: ElementVector<U> = std::array::from_fn(|i| u[dofs.global(nodes, i)]);
        if !self.mesh.is_periodic() {
            return periodic;
        }
        let x = self.mesh.element_coordinates(e);
        let h = &self.average_gradient;
        std::array::from_fn(|i| {
            let (a, c) = (dofs.node(i), dofs.component(i));
            periodic[i] + (0..D).map(|j| h[c][j] * x[a][j]).sum::<f64>()
        })
    }

    /// Sets the average displacement gradient `H` carried across a periodic mesh's sides
    /// (`H = diag(lambda_1 - 1, 0, lambda_3 - 1)` under biaxial compression).
    pub fn set_average_gradient(&mut self, h: [[f64; D]; D]) {
        self.average_gradient = h;
    }

    /// The average displacement gradient carried across a periodic mesh's sides.
    pub fn average_gradient(&self) -> &[[f64; D]; D] {
        &self.average_gradient
    }

    /// The free unknowns when `bc` is prescribed, increasing; position = index in the reduced system.
    pub fn free_dofs(&mut self, bc: &Dirichlet) -> Result<&[usize]> {
        if self.pattern.as_ref().is_none_or(|p| p.constrained != bc.dofs()) {
            self.pattern_for(bc, &[], &|| Vec::new())?;
        }
        Ok(&self.pattern.as_ref().expect("built above").free)
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
        self.assemble_with(u, bc, lift, with_tangent, &NoAddedEnergy)
    }

    /// [`System::assemble`] of the strain energy plus `added` (whose groups join the pattern).
    pub fn assemble_with(
        &mut self,
        u: &[f64],
        bc: &Dirichlet,
        lift: Option<&[f64]>,
        with_tangent: bool,
        added: &dyn AddedEnergy,
    ) -> Result<Assembled> {
        self.assemble_penalised(u, bc, lift, with_tangent, added, Penalty::Augmentation(1.0))
    }

    /// [`System::assemble_with`] with the multipliers' constraint penalised as `penalty` says
    /// ([`crate::fem::element::mixed`]; the method of multipliers raises it where they converge slowly).
    pub fn assemble_penalised(
        &mut self,
        u: &[f64],
        bc: &Dirichlet,
        lift: Option<&[f64]>,
        with_tangent: bool,
        added: &dyn AddedEnergy,
        penalty: Penalty,
    ) -> Result<Assembled> {
        assert_eq!(u.len(), self.num_dofs(), "displacement vector length");
        assert!(
            lift.is_none_or(|l| l.len() == bc.len()),
            "one lift value per prescribed unknown"
        );
        let start = Instant::now();
        self.pattern_for(bc, added.groups(), &|| added.likely_groups())?;
        let pattern = self.pattern.as_ref().expect("built above");
        let total = if with_tangent {
            *pattern.offsets.last().unwrap_or(&0)
        } else {
            0
        };
        // Every element writes all of its slice, so stale values need no zeroing.
        let mut entries = std::mem::take(&mut self.entries);
        entries.resize(total, 0.0);
        let mut chunks = split(&mut entries, &pattern.offsets, with_tangent);
        let group_chunks = chunks.split_off(self.mesh.elements().len());
        let results = chunks
            .into_par_iter()
            .enumerate()
            .with_min_len(32)
            .map(|(e, chunk)| self.element_contribution(pattern, e, (u, penalty), lift, chunk))
            .collect::<Result<Vec<_>>>()?;
        let added_results: Vec<(Block, Vec<f64>)> = group_chunks
            .into_par_iter()
            .enumerate()
            .with_min_len(64)
            .map(|(g, chunk)| group_contribution(pattern, added, g, u, lift, chunk))
            .collect();

        let mut residual = vec![0.0; pattern.free.len()];
        let mut reactions = vec![0.0; bc.len()];
        let (mut energy, mut potential, mut min_jacobian) = (0.0, 0.0, f64::INFINITY);
        let dofs = self.mesh.dofs();
        for (nodes, (state, lifted)) in self.mesh.elements().iter().zip(&results) {
            for (i, (force, lift)) in state.force.iter().zip(lifted).enumerate() {
                match pattern.slots[dofs.global(nodes, i)] {
                    Slot::Free(f) => residual[f] += force + lift,
                    Slot::Fixed(c) => reactions[c] += force,
                }
            }
            energy += state.energy;
            potential += state.potential;
            min_jacobian = min_jacobian.min(state.min_jacobian);
        }
        let mut added_energy = 0.0;
        for (dofs, (block, lifted)) in pattern.groups.iter().zip(&added_results) {
            for (i, &dof) in dofs.iter().enumerate() {
                match pattern.slots[dof] {
                    Slot::Free(f) => residual[f] += block.gradient[i] + lifted[i],
                    Slot::Fixed(c) => reactions[c] += block.gradient[i],
                }
            }
            added_energy += block.energy;
        }
        let diagonal = added.diagonal(u);
        if let Some(diagonal) = &diagonal {
            for (dof, &g) in diagonal.gradient.iter().enumerate() {
                match pattern.slots[dof] {
                    Slot::Free(f) => residual[f] += g,
                    Slot::Fixed(c) => reactions[c] += g,
                }
            }
            added_energy += diagonal.energy;
        }
        let tangent = with_tangent.then(|| {
            let mut values = pattern.tangent_values(&entries, self.mesh.elements().len());
            if let Some(diagonal) = &diagonal {
                for (&position, &dof) in pattern.diagonal.iter().zip(&pattern.free) {
                    values[position] += diagonal.curvature[dof];
                }
            }
            Tangent::on(Arc::clone(&pattern.symbolic), values)
        });
        self.entries = entries;
        Ok(Assembled {
            residual,
            tangent,
            reactions,
            energy,
            potential,
            added_energy,
            min_jacobian,
            pattern: pattern.id,
            structure: pattern.structure,
            elapsed: start.elapsed(),
        })
    }

    /// `assembled` (of the current pattern, with its tangent) with `curvature[dof]` added to
    /// the tangent's diagonal entry of every free unknown: the assembly of the strain energy
    /// plus `sum_i c_i (u_i - u0_i)^2 / 2` centred at `assembled`'s own state (which adds
    /// neither energy nor force), without assembling again. Panics if the pattern has changed
    /// since or the tangent is missing.
    pub fn with_diagonal_added(&self, assembled: &Assembled, curvature: &[f64]) -> Assembled {
        let start = Instant::now();
        let pattern = self.pattern.as_ref().expect("assembled before");
        assert_eq!(pattern.id, assembled.pattern, "the assembly is of the current pattern");
        let mut tangent = assembled.tangent.clone().expect("assembled with the tangent");
        for (&position, &dof) in pattern.diagonal.iter().zip(&pattern.free) {
            tangent.values_mut()[position] += curvature[dof];
        }
        Assembled {
            residual: assembled.residual.clone(),
            tangent: Some(tangent),
            reactions: assembled.reactions.clone(),
            elapsed: start.elapsed(),
            ..*assembled
        }
    }

    /// Element `e`'s state at `u` (with the multipliers' constraint penalised by `penalty`), its
    /// lifting force `K_e lift_e`, and its free-free block into `chunk`.
    fn element_contribution(
        &self,
        pattern: &Pattern,
        e: usize,
        (u, penalty): (&[f64], Penalty),
        lift: Option<&[f64]>,
        chunk: &mut [f64],
    ) -> Result<(ElementState<U>, ElementVector<U>)> {
        let (dofs, nodes) = (self.mesh.dofs(), &self.mesh.elements()[e]);
        let slots: [Slot; U] = std::array::from_fn(|i| pattern.slots[dofs.global(nodes, i)]);
        let needs_tangent = !chunk.is_empty() || lift.is_some();
        let mut k = [[0.0; U]; U];
        let state = self.element_state(
            e,
            &self.element_displacements(e, u),
            &self.element_multipliers(e, u),
            penalty,
            needs_tangent.then_some(&mut k),
        )?;
        let mut lifted = [0.0; U];
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
            let free = || {
                slots.iter().enumerate().filter_map(|(a, s)| match s {
                    Slot::Free(f) => Some((a, *f)),
                    Slot::Fixed(_) => None,
                })
            };
            let mut entries = chunk.iter_mut();
            for (a, row) in free() {
                for (b, _) in free().filter(|&(_, col)| row >= col) {
                    *entries.next().expect("chunk sized by the pattern") = k[a][b];
                }
            }
        }
        Ok((state, lifted))
    }

    /// The cached pattern for `bc`'s prescribed unknowns and the added `groups`: the stored
    /// entries are kept when the groups change but fit in them, and rebuilt otherwise.
    fn pattern_for(
        &mut self,
        bc: &Dirichlet,
        groups: &[Vec<usize>],
        likely: &dyn Fn() -> Vec<Vec<usize>>,
    ) -> Result<&Pattern> {
        let n = self.mesh.num_dofs();
        if let Some(&bad) = bc.dofs().iter().chain(groups.iter().flatten()).find(|&&d| d >= n) {
            return Err(Error::invalid(
                "prescribed or coupled unknown",
                bad,
                &format!("[0, {n})"),
            ));
        }
        Pattern::refresh(&mut self.pattern, &self.mesh, bc.dofs(), groups, likely);
        Ok(self.pattern.as_ref().expect("just built"))
    }
}

/// Group `g`'s block, its lifting force `K_g lift_g`, and its free-free block into `chunk`.
fn group_contribution(
    pattern: &Pattern,
    added: &dyn AddedEnergy,
    g: usize,
    u: &[f64],
    lift: Option<&[f64]>,
    chunk: &mut [f64],
) -> (Block, Vec<f64>) {
    let dofs = &pattern.groups[g];
    let n = dofs.len();
    let block = added.block(g, u, !chunk.is_empty() || lift.is_some());
    let mut lifted = vec![0.0; n];
    if let Some(lift) = lift {
        for (b, &dof) in dofs.iter().enumerate() {
            if let Slot::Fixed(c) = pattern.slots[dof] {
                for (a, l) in lifted.iter_mut().enumerate() {
                    *l += block.hessian[a * n + b] * lift[c];
                }
            }
        }
    }
    if !chunk.is_empty() {
        let free: Vec<(usize, usize)> = (0..n)
            .filter_map(|i| match pattern.slots[dofs[i]] {
                Slot::Free(f) => Some((i, f)),
                Slot::Fixed(_) => None,
            })
            .collect();
        let mut entries = chunk.iter_mut();
        for &(a, row) in &free {
            for &(b, _) in free.iter().filter(|&&(_, col)| row >= col) {
                *entries.next().expect("chunk sized by the pattern") = block.hessian[a * n + b];
            }
        }
    }
    (block, lifted)
}

/// One mutable slice of `values` per block (empty ones when no tangent is assembled).
fn split<'a>(values: &'a mut [f64], offsets: &[usize], with_tangent: bool) -> Vec<&'a mut [f64]> {
    let blocks = offsets.len() - 1;
    if !with_tangent {
        return (0..blocks).map(|_| <&mut [f64]>::default()).collect();
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
