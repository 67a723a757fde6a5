//! A patch of tissue under biaxial compression: its boundary conditions at `(d, d_3 = R d)`, its
//! homogeneous state, and the first bifurcation of the perfect patch.
//!
//! Periodic sides carry the average stretch across: the unknowns are the periodic part `w` of
//! `u = H X + w`, with `H = diag(-d, 0, -d_3)` ([`crate::fem::System::set_average_gradient`]);
//! the bottom holds `u_Y = 0` and one bottom node `w_X = w_Z = 0` (the rigid translations of a
//! periodic patch). Symmetry sides prescribe `u_X = 0` at `X = 0`, `u_X = -d Lx` at `X = Lx`,
//! `u_Z = 0` at `Z = 0`, `u_Z = -d_3 Lz` at `Z = Lz`, and the bottom `u_Y = 0`, as the strip's
//! model conditions do.
//!
//! The homogeneous state (each layer at `diag(lambda_1, lambda_2, lambda_3)`,
//! [`biaxial_state`]) is represented exactly by the hexahedra, so it is set analytically and
//! checked to be in equilibrium; the first bifurcation is found on it as on the strip
//! ([`super::bifurcation`]): the first `d` at which the tangent has a negative pivot.

use super::bifurcation::{first_instability, BifurcationSettings};
use super::continuation::Followed;
use crate::error::{Error, Result};
use crate::fem::added::NoAddedEnergy;
use crate::fem::assembly::norm;
use crate::fem::lanczos::inverse_lanczos;
use crate::fem::memory::MemoryEstimate;
use crate::fem::{Assembled, Dirichlet, PatchSystem, SparseLdlt, Tangent};
use crate::homogeneous::{biaxial_state, normal_stress, BiaxialState};
use crate::material::{Bilayer, Tissue};
use crate::mesh::{Mesh, PatchSpec, BACK, BOTTOM, FRONT, LEFT, RIGHT, TOP, X, Y, Z};
use serde::Serialize;

/// The boundary conditions of a patch whose sides have moved in by `d` along X and `d3` along Z
/// (fractions of its lengths; 0 under growth), and the average displacement gradient its
/// periodic sides carry (zero for symmetry sides).
pub fn patch_conditions(mesh: &Mesh<3, 27>, d: f64, d3: f64) -> Result<(Dirichlet, [[f64; 3]; 3])> {
    let dofs = mesh.dofs();
    let mut pairs: Vec<(usize, f64)> = mesh.node_set(BOTTOM).iter().map(|&n| (dofs.dof(n, Y), 0.0)).collect();
    if mesh.is_periodic() {
        let anchor = mesh.node_set(BOTTOM)[0];
        pairs.extend([(dofs.dof(anchor, X), 0.0), (dofs.dof(anchor, Z), 0.0)]);
        return Ok((
            Dirichlet::new(pairs)?,
            [[-d, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, -d3]],
        ));
    }
    let [length_x, _, length_z] = side_lengths(mesh);
    for (set, component, value) in [
        (LEFT, X, 0.0),
        (RIGHT, X, -d * length_x),
        (BACK, Z, 0.0),
        (FRONT, Z, -d3 * length_z),
    ] {
        pairs.extend(mesh.node_set(set).iter().map(|&n| (dofs.dof(n, component), value)));
    }
    Ok((Dirichlet::new(pairs)?, [[0.0; 3]; 3]))
}

/// `(Lx, -, Lz)` of a patch.
fn side_lengths(mesh: &Mesh<3, 27>) -> [f64; 3] {
    let spec = mesh.patch_spec();
    [spec.length_x, 0.0, spec.length_z]
}

/// The unknowns of the homogeneous `state` on a patch: `u_Y = (lambda_2s - 1)(Y + D)` in the
/// substrate and `(lambda_2s - 1) D + (lambda_2l - 1) Y` in the layer, and on symmetry sides
/// `u_X = -d X`, `u_Z = -d_3 Z` under compression (on periodic sides the average gradient
/// carries those; under growth the sides are held).
pub fn homogeneous_patch_displacement(mesh: &Mesh<3, 27>, state: &BiaxialState) -> Vec<f64> {
    let depth = mesh.patch_spec().depth;
    let (mut u, dofs) = (vec![0.0; mesh.num_dofs()], mesh.dofs());
    let in_plane = if mesh.is_periodic() { 0.0 } else { 1.0 };
    let [shortening_x, shortening_z] = state.end_shortening();
    for (n, &[x, y, z]) in mesh.coordinates().iter().enumerate() {
        u[dofs.dof(n, X)] = -in_plane * shortening_x * x;
        u[dofs.dof(n, Y)] =
            (state.lambda2_substrate - 1.0) * (y.min(0.0) + depth) + (state.lambda2_layer - 1.0) * y.max(0.0);
        u[dofs.dof(n, Z)] = -in_plane * shortening_z * z;
    }
    u
}

/// The unknowns of the homogeneous `state` on the patch of `system`: its displacement
/// ([`homogeneous_patch_displacement`]) followed, with multipliers, by each layer's pressure.
pub fn homogeneous_patch_unknowns(system: &PatchSystem, materials: &Bilayer, state: &BiaxialState) -> Result<Vec<f64>> {
    let u = homogeneous_patch_displacement(system.mesh(), state);
    if !system.has_multipliers() {
        return Ok(u);
    }
    let (layer, substrate) = (state.layer_stretches(), state.substrate_stretches());
    let p_layer = homogeneous_pressure(materials.layer_tissue(), layer, materials.incompressible)?;
    let p_substrate = homogeneous_pressure(materials.substrate_tissue(), substrate, materials.incompressible)?;
    Ok(system.with_homogeneous_multipliers(u, p_layer, p_substrate))
}

/// The residual of an assembly (with its tangent) at `u` relative to the forces the state's
/// displacements carry, `|r| / (max |K_ij| |u|)`: on a periodic patch under an average
/// gradient the internal forces cancel at equilibrium and no reaction sets a scale.
pub fn relative_residual(assembled: &Assembled, u: &[f64]) -> f64 {
    let k = assembled.tangent.as_ref().expect("assembled with the tangent");
    let largest = k.as_ref().val().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assembled.residual_norm() / (largest * norm(u)).max(f64::MIN_POSITIVE)
}

/// The pressure conjugate to `ln J` of a tissue at the principal `stretches`: the one that
/// keeps an incompressible tissue free of `sigma_22` (`p = -lambda_2 P_rest,22`), else
/// `kappa (ln J - ln Jg)` with the bulk modulus the tissue carries.
fn homogeneous_pressure(tissue: Tissue, stretches: [f64; 3], incompressible: bool) -> Result<f64> {
    let split = tissue.volumetric_split();
    match incompressible {
        true => Ok(-stretches[1] * normal_stress(&split.rest, stretches)?),
        false => Ok(split.bulk * (stretches.iter().product::<f64>().ln() - split.log_volume)),
    }
}

/// The eigenvector of the tangent at the state `u` (with `bc` prescribed) whose eigenvalue is
/// nearest zero, and that eigenvalue, by `solves` inverse-Lanczos steps: where the state has
/// just turned unstable, its unstable direction. Scaled as `full_mode`.
pub fn nearest_singular_mode(
    system: &mut PatchSystem,
    u: &[f64],
    bc: &Dirichlet,
    solves: usize,
) -> Result<(Vec<f64>, f64)> {
    let assembled = system.assemble_for_stability(u, bc, &NoAddedEnergy)?;
    let k = assembled.tangent.expect("assembled with the tangent");
    let mut solver = SparseLdlt::new(k.symbolic());
    solver.factorize(k.as_ref());
    let (free_mode, eigenvalue) = inverse_lanczos(&mut solver, k.as_ref(), solves, 1e-12)?;
    Ok((full_mode(system, bc, &free_mode)?, eigenvalue))
}

/// A mode on the free unknowns as a vector of all unknowns (zero where prescribed), scaled so
/// that the largest top-surface `|u_Y|` is 1.
fn full_mode(system: &mut PatchSystem, bc: &Dirichlet, free_mode: &[f64]) -> Result<Vec<f64>> {
    let free = system.free_dofs(bc)?.to_vec();
    let mut mode = vec![0.0; system.num_dofs()];
    for (&dof, &v) in free.iter().zip(free_mode) {
        mode[dof] = v;
    }
    let mesh = system.mesh();
    let largest = mesh
        .node_set(TOP)
        .iter()
        .fold(0.0f64, |m, &n| m.max(mode[mesh.dofs().dof(n, Y)].abs()));
    if largest > 0.0 {
        mode.iter_mut().for_each(|v| *v /= largest);
    }
    Ok(mode)
}

/// The first bifurcation of a perfect patch.
#[derive(Clone, Debug, Serialize)]
pub struct PatchBifurcation {
    /// Midpoint of the final bracket.
    pub d: f64,
    /// `(d_stable, d_unstable)`: no negative pivot at the first, some at the second.
    pub bracket: (f64, f64),
    /// Negative pivots at `d_unstable` (two for a mirror pair of modes, more where several
    /// admissible wave vectors are critical together).
    pub negative_pivots: usize,
    /// Every `(d, negative pivots)` evaluated, in order.
    pub path: Vec<(f64, usize)>,
    /// Free unknowns of the tangent.
    pub unknowns: usize,
    /// The eigenvector of the tangent's smallest eigenvalue at `d_stable` (all unknowns, zero
    /// where prescribed), scaled so that the largest top-surface `|u_Y|` is 1: one member of
    /// the critical modes (any combination of them where several are critical together).
    #[serde(skip)]
    pub mode: Vec<f64>,
    /// That smallest eigenvalue.
    pub eigenvalue: f64,
}

/// The homogeneous path of a patch under `d_3 = biaxiality d`, with its reused factorisation.
pub struct PatchPath<'a> {
    materials: &'a Bilayer,
    patch: BiaxialPatch,
    solver: Option<SparseLdlt>,
    path: Vec<(f64, usize)>,
    unknowns: usize,
}

impl<'a> PatchPath<'a> {
    /// The path of the perfect patch of `spec` under `d_3 = biaxiality d`.
    pub fn new(materials: &'a Bilayer, spec: PatchSpec, biaxiality: f64) -> Result<Self> {
        if !(biaxiality.is_finite() && (0.0..=1.0).contains(&biaxiality)) {
            return Err(Error::invalid("biaxial", biaxiality, "[0, 1]"));
        }
        Ok(PatchPath {
            materials,
            patch: BiaxialPatch::new(
                PatchSystem::on_patch(Mesh::patch(spec)?, materials)?,
                biaxiality,
                Vec::new(),
            ),
            solver: None,
            path: Vec::new(),
            unknowns: 0,
        })
    }

    /// The same path with `u_Z = 0` everywhere: a slab in plane strain.
    pub fn in_plane_strain(mut self) -> Self {
        let mesh = self.patch.system().mesh();
        let held = (0..mesh.num_nodes()).map(|n| mesh.dofs().dof(n, Z)).collect();
        self.patch.hold(held);
        self
    }

    /// The system.
    pub fn system(&self) -> &PatchSystem {
        self.patch.system()
    }

    /// The homogeneous state at `d`, the conditions there, and its unknowns.
    pub fn homogeneous(&mut self, d: f64) -> Result<(BiaxialState, Dirichlet, Vec<f64>)> {
        let state = biaxial_state(self.materials, d, self.patch.biaxiality() * d)?;
        let bc = self.patch.load_to(d)?;
        let u = homogeneous_patch_unknowns(self.patch.system(), self.materials, &state)?;
        Ok((state, bc, u))
    }

    /// Negative pivots of the tangent at the homogeneous state `d`, which must be a discrete
    /// equilibrium ([`relative_residual`] at most 1e-10).
    pub fn negative_pivots(&mut self, d: f64) -> Result<usize> {
        let (negative, _, _) = self.factorise(d)?;
        self.path.push((d, negative));
        Ok(negative)
    }

    /// Assembles and factorises the tangent at the homogeneous state `d`: its negative pivots,
    /// the tangent and the conditions there.
    fn factorise(&mut self, d: f64) -> Result<(usize, Tangent, Dirichlet)> {
        let (_, bc, u) = self.homogeneous(d)?;
        let assembled = self
            .patch
            .system_mut()
            .assemble_for_stability(&u, &bc, &NoAddedEnergy)?;
        let relative = relative_residual(&assembled, &u);
        if relative > 1e-10 {
            return Err(Error::Solver(format!(
                "the homogeneous state at d = {d} is not a discrete equilibrium of the patch (relative residual {relative:.2e})"
            )));
        }
        let k = assembled.tangent.expect("assembled with the tangent");
        self.unknowns = k.nrows();
        let solver = self.solver.get_or_insert_with(|| SparseLdlt::new(k.symbolic()));
        solver.factorize(k.as_ref());
        Ok((solver.negative_pivots().expect("just factorised"), k, bc))
    }

    /// What the path's factorisations will need in memory: the tangent's pattern (at the
    /// unloaded state) and its symbolic factor, analysed here and kept for the path, before any
    /// factor is allocated.
    pub fn memory_estimate(&mut self) -> Result<MemoryEstimate> {
        let (_, bc, u) = self.homogeneous(0.0)?;
        let assembled = self.patch.system_mut().assemble(&u, &bc, None, true)?;
        let k = assembled.tangent.expect("assembled with the tangent");
        let solver = self.solver.get_or_insert_with(|| SparseLdlt::new(k.symbolic()));
        let elements = self.patch.system().mesh().elements().len();
        Ok(MemoryEstimate::of_factor(
            k.nrows(),
            elements,
            k.compute_nnz(),
            solver.factor_size(),
        ))
    }

    /// The first bifurcation along the path (the scan and bisection of `settings`), telling
    /// `progress` every `(d, negative pivots)` evaluated.
    pub fn bifurcation(
        &mut self,
        settings: &BifurcationSettings,
        progress: &mut dyn FnMut(f64, usize),
    ) -> Result<PatchBifurcation> {
        let (stable, unstable, negative_pivots) = first_instability(
            |d| {
                let negative = self.negative_pivots(d)?;
                progress(d, negative);
                Ok(negative)
            },
            settings,
        )?;
        let (_, k, bc) = self.factorise(stable)?;
        let solver = self.solver.as_mut().expect("factorised above");
        let (free_mode, eigenvalue) = inverse_lanczos(solver, k.as_ref(), settings.mode_solves, 1e-12)?;
        let mode = full_mode(self.patch.system_mut(), &bc, &free_mode)?;
        Ok(PatchBifurcation {
            d: 0.5 * (stable + unstable),
            bracket: (stable, unstable),
            negative_pivots,
            path: std::mem::take(&mut self.path),
            unknowns: self.unknowns,
            mode,
            eigenvalue,
        })
    }
}

mod biaxial;
mod post_buckling;
mod self_contact;
mod spectrum;
pub use biaxial::BiaxialPatch;
pub use post_buckling::{PatchImperfection, PatchProtocol};
pub use self_contact::surface_crosses_itself;
pub use spectrum::{
    classify, height_spectrum, surface_spectrum, Direction, SurfacePattern, WaveVector, SECOND_DIRECTION,
};

/// A small patch of 4 x 3 elements over 8 x 6, one element through the layer and one through
/// the substrate (the surface tests' mesh).
#[cfg(test)]
fn small_patch(sides: crate::mesh::Sides) -> Mesh<3, 27> {
    Mesh::patch(PatchSpec {
        nx: 4,
        nz: 3,
        length_x: 8.0,
        length_z: 6.0,
        layer_elements: 1,
        substrate_elements: 1,
        top_substrate_thickness: 3.0,
        depth: 3.0,
        sides,
        element: crate::mesh::ElementKind::Displacement,
    })
    .unwrap()
}

#[cfg(test)]
mod tests;
