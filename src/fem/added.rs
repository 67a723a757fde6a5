//! Energies added to the elastic one, each a sum of terms that couple a few unknowns: contact
//! penalties ([`super::contact`]) and the viscous stabilisation of a path across a snap.
//!
//! A term is a *group* of global unknowns with its energy, gradient and (dense) Hessian. The
//! assembly treats a group like an element: its block enters the sparsity pattern of `K_ff`,
//! which is rebuilt (and the factorisation re-analysed) only when a group couples unknowns
//! that the pattern does not couple yet, e.g. when the contact search finds a node facing a
//! segment across a closing trough (a pair with a symmetry plane couples one node's unknowns,
//! which every pattern holds). A term on single unknowns (a
//! damper) is a *diagonal* instead: it adds to the diagonal of `K_ff`, which every pattern holds,
//! so it costs no groups and never changes the pattern.

/// One group's contribution at a displacement: `E`, `dE/du` and `d2E/du2` (row-major, empty
/// when the tangent is not requested), over the group's unknowns in their listed order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Block {
    pub energy: f64,
    pub gradient: Vec<f64>,
    pub hessian: Vec<f64>,
}

/// A sum of terms of one unknown each, `E = sum_i e_i(u_i)`, over all unknowns: `E`, `dE/du`
/// and the diagonal `d2E/du_i2`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagonal {
    pub energy: f64,
    pub gradient: Vec<f64>,
    pub curvature: Vec<f64>,
}

impl Diagonal {
    /// The quadratic `sum_i c_i (u_i - r_i)^2 / 2` at `u`, with the curvatures `c` and the
    /// reference `r` (over the unknowns that `c` covers): a damper's or a shift's.
    pub fn quadratic(curvature: Vec<f64>, u: &[f64], reference: &[f64]) -> Self {
        let gradient: Vec<f64> = (0..curvature.len())
            .map(|i| curvature[i] * (u[i] - reference[i]))
            .collect();
        let energy = 0.5
            * gradient
                .iter()
                .zip(u.iter().zip(reference))
                .map(|(g, (x, r))| g * (x - r))
                .sum::<f64>();
        Diagonal {
            energy,
            gradient,
            curvature,
        }
    }
}

/// An energy added to the strain energy.
pub trait AddedEnergy: Sync {
    /// The global unknowns of every group (fixed until the owner changes them).
    fn groups(&self) -> &[Vec<usize>];

    /// Group `g`'s contribution at the full displacement `u` (Hessian only if `with_tangent`).
    fn block(&self, g: usize, u: &[f64], with_tangent: bool) -> Block;

    /// The diagonal terms at `u`, if the energy has any.
    fn diagonal(&self, _u: &[f64]) -> Option<Diagonal> {
        None
    }

    /// Sets of unknowns that groups to come are likely to couple: when the pattern has to grow
    /// for new groups anyway, it stores these couplings too, so that the next new groups need
    /// no new analysis (e.g. the neighbours of a closing trough's contact pairs).
    fn likely_groups(&self) -> Vec<Vec<usize>> {
        Vec::new()
    }

    /// The fraction of the move from `u` to `trial` (full vectors) at which the first group
    /// that carries no force at `u` starts to carry one (1 if none does): a Newton step from a
    /// tangent without a term overshoots where the term switches on (a contact pair that closes
    /// in the step), so the line search starts there.
    fn switch_on_fraction(&self, _u: &[f64], _trial: &[f64]) -> f64 {
        1.0
    }
}

/// Nothing added: the plain elastic problem.
pub struct NoAddedEnergy;

impl AddedEnergy for NoAddedEnergy {
    fn groups(&self) -> &[Vec<usize>] {
        &[]
    }

    fn block(&self, g: usize, _: &[f64], _: bool) -> Block {
        unreachable!("NoAddedEnergy has no group {g}")
    }
}

/// The sum of several added energies; its groups are theirs, concatenated in order.
pub struct Sum<'a> {
    parts: Vec<&'a dyn AddedEnergy>,
    groups: Vec<Vec<usize>>,
    /// Group `g` is group `owner[g].1` of part `owner[g].0`.
    owner: Vec<(usize, usize)>,
}

impl<'a> Sum<'a> {
    pub fn new(parts: Vec<&'a dyn AddedEnergy>) -> Self {
        let mut groups = Vec::new();
        let mut owner = Vec::new();
        for (p, part) in parts.iter().enumerate() {
            groups.extend(part.groups().iter().cloned());
            owner.extend((0..part.groups().len()).map(|g| (p, g)));
        }
        Sum { parts, groups, owner }
    }
}

impl AddedEnergy for Sum<'_> {
    fn groups(&self) -> &[Vec<usize>] {
        &self.groups
    }

    fn block(&self, g: usize, u: &[f64], with_tangent: bool) -> Block {
        let (part, local) = self.owner[g];
        self.parts[part].block(local, u, with_tangent)
    }

    fn likely_groups(&self) -> Vec<Vec<usize>> {
        self.parts.iter().flat_map(|p| p.likely_groups()).collect()
    }

    fn switch_on_fraction(&self, u: &[f64], trial: &[f64]) -> f64 {
        self.parts
            .iter()
            .fold(1.0, |m, p| m.min(p.switch_on_fraction(u, trial)))
    }

    fn diagonal(&self, u: &[f64]) -> Option<Diagonal> {
        self.parts.iter().filter_map(|p| p.diagonal(u)).reduce(|mut sum, term| {
            sum.energy += term.energy;
            sum.gradient.iter_mut().zip(&term.gradient).for_each(|(a, b)| *a += b);
            sum.curvature.iter_mut().zip(&term.curvature).for_each(|(a, b)| *a += b);
            sum
        })
    }
}
