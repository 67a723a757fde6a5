//! Growth: the multiplicative split `F = Fe Fg` (Rodriguez, Hoger and McCulloch 1994). A
//! tissue grows by `Fg` into a stress-free configuration and is then deformed elastically by
//! `Fe = F Fg^-1`; its energy per reference volume is `Jg W(Fe)` with `Jg = det Fg`
//! (`docs/model.md`, "Growth"). Fibre directions are those of the grown configuration, so
//! `I4 = N . Fe^T Fe N`.
//!
//! [`Grown`] wraps any strain energy, so every analysis of a law (the homogeneous state, both
//! linear-stability methods, the ellipticity check) gets growth from this one file. With
//! `Fg = diag(g1, g2, g3)` the chain rule is a scaling: `P_iJ = Jg P^e_iJ(Fe) / g_J` and
//! `A_iJkL = Jg A^e_iJkL(Fe) / (g_J g_L)`. Plane strain grows in its own plane (`g3 = 1`); the
//! surface of a three-dimensional patch grows along `X` and `Z`.

use super::{FullResponse, Response, StrainEnergy, Tensor2};
use crate::error::Result;
use num_dual::DualNum;

/// A principal growth tensor `Fg = diag(g1, g2, g3)` (`Y` through the thickness; plane strain
/// keeps `g3 = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Growth {
    /// `(g1, g2, g3)`: growth along `X`, `Y` and `Z`.
    pub stretches: [f64; 3],
}

impl Growth {
    /// No growth, `Fg = I`.
    pub const NONE: Growth = Growth {
        stretches: [1.0, 1.0, 1.0],
    };

    /// Growth `g` along the surface only, `Fg = diag(g, 1, 1)`.
    pub fn tangential(g: f64) -> Self {
        Growth::in_surface(g, 1.0, false)
    }

    /// Growth `g` of the in-plane area, `Fg = diag(g, g, 1)`: a layer thickens as it lengthens.
    pub fn area(g: f64) -> Self {
        Growth::in_surface(g, 1.0, true)
    }

    /// Growth `g1` along `X` and `g3` along `Z` in the surface, `Fg = diag(g1, g2, g3)`, with
    /// the thickness growing as the length does (`g2 = g1`) if `thickens`, else not
    /// (`g2 = 1`): `diag(g, 1, g)` is the surface's area growth.
    pub fn in_surface(g1: f64, g3: f64, thickens: bool) -> Self {
        Growth {
            stretches: [g1, if thickens { g1 } else { 1.0 }, g3],
        }
    }

    /// `Jg = det Fg`.
    pub fn jacobian(&self) -> f64 {
        self.stretches.iter().product()
    }

    pub fn is_identity(&self) -> bool {
        *self == Growth::NONE
    }

    /// Whether `Z` is ungrown, so that plane strain (`F33 = 1`) is elastic plane strain too.
    fn is_plane(&self) -> bool {
        self.stretches[2] == 1.0
    }

    /// `g_J` for the column `J` of a 3x3 gradient.
    fn along(&self, column: usize) -> f64 {
        self.stretches[column]
    }

    /// `Fe = F Fg^-1` of a full gradient (`Fe_iJ = F_iJ / g_J`).
    fn elastic_full<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> [D; 9] {
        std::array::from_fn(|a| f[a] * (1.0 / self.along(a % 3)))
    }

    /// `Fe = F Fg^-1` of a plane gradient (the in-plane block; `Fe_33 = 1 / g3`).
    pub fn elastic_plane(&self, f: &Tensor2) -> Tensor2 {
        std::array::from_fn(|a| f[a] / self.stretches[a % 2])
    }
}

/// A strain energy `W` of a tissue that has grown by `growth`: `Jg W(F Fg^-1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grown<M> {
    pub energy: M,
    pub growth: Growth,
}

impl<M> Grown<M> {
    /// `energy` without growth.
    pub fn ungrown(energy: M) -> Self {
        Grown {
            energy,
            growth: Growth::NONE,
        }
    }

    /// This energy with its growth replaced by `growth`.
    pub fn with_growth(self, growth: Growth) -> Self {
        Grown { growth, ..self }
    }
}

/// The grown response from the elastic one at `Fe`: each gradient index `a` scaled by
/// `Jg / g_J(a)`, each pair by `Jg / (g_J(a) g_J(b))`.
fn scale_response<const N: usize>(
    mut r: super::ResponseOf<N>,
    jg: f64,
    along: impl Fn(usize) -> f64,
) -> super::ResponseOf<N> {
    r.energy *= jg;
    for a in 0..N {
        r.stress[a] *= jg / along(a);
        for b in 0..N {
            r.tangent[a][b] *= jg / (along(a) * along(b));
        }
    }
    r
}

impl<M: StrainEnergy> StrainEnergy for Grown<M> {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        self.energy.density(&self.growth.elastic_full(f)) * self.growth.jacobian()
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        if self.growth.is_identity() {
            return self.energy.plane_response(f);
        }
        if !self.growth.is_plane() {
            return crate::material::differentiated_response(self, f);
        }
        let g = self.growth;
        let elastic = self.energy.plane_response(&g.elastic_plane(f));
        scale_response(elastic, g.jacobian(), |a| g.stretches[a % 2])
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        if self.growth.is_identity() {
            return self.energy.plane_stress(f);
        }
        if !self.growth.is_plane() {
            return crate::material::differentiated_stress(self, f);
        }
        let g = self.growth;
        let (w, p) = self.energy.plane_stress(&g.elastic_plane(f));
        let jg = g.jacobian();
        (w * jg, std::array::from_fn(|a| p[a] * jg / g.stretches[a % 2]))
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        if self.growth.is_identity() {
            return self.energy.response_3d(f);
        }
        let g = self.growth;
        let elastic = self.energy.response_3d(&g.elastic_full(f));
        scale_response(elastic, g.jacobian(), |a| g.along(a % 3))
    }

    fn admissible(&self, f: &[f64; 9]) -> Result<()> {
        self.energy.admissible(&self.growth.elastic_full(f))
    }

    fn bounded_domain(&self) -> bool {
        self.energy.bounded_domain()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Bilayer, Hyperelastic};
    use crate::parameters::Parameters;

    /// Central differences of `Jg W(F Fg^-1)`, evaluated by the plain energy at `Fe`.
    fn grown_energy<M: Hyperelastic>(m: &M, growth: Growth, f: &Tensor2) -> f64 {
        let fe = growth.elastic_plane(f);
        m.energy(&fe).unwrap() * growth.jacobian()
    }

    fn difference(w: impl Fn(&Tensor2) -> f64, f: &Tensor2, a: usize, h: f64) -> f64 {
        let (mut plus, mut minus) = (*f, *f);
        plus[a] += h;
        minus[a] -= h;
        (w(&plus) - w(&minus)) / (2.0 * h)
    }

    /// The grown response of `m` against central differences of `Jg W(F Fg^-1)`.
    fn check_against_differences<M: Hyperelastic + Copy>(m: M, growth: Growth, f: &Tensor2) {
        let r = Grown::ungrown(m).with_growth(growth).response(f).unwrap();
        let w = |x: &Tensor2| grown_energy(&m, growth, x);
        assert!((r.energy - w(f)).abs() < 1e-13 * r.energy.abs().max(1.0));
        let h = 1e-5;
        for a in 0..4 {
            let fd = difference(w, f, a, h);
            assert!(
                (r.stress[a] - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                "P[{a}] {} vs {fd}",
                r.stress[a]
            );
            let stress_a = |x: &Tensor2| difference(w, x, a, h);
            for b in 0..4 {
                let fd = difference(stress_a, f, b, 1e-4);
                let exact = r.tangent[a][b];
                assert!(
                    (exact - fd).abs() < 2e-4 * (1.0 + fd.abs()),
                    "A[{a}][{b}] {exact} vs {fd}"
                );
            }
        }
    }

    #[test]
    fn grown_stress_and_tangent_are_the_derivatives_of_the_grown_energy() {
        let materials = Bilayer::new(&Parameters {
            beta: 0.6,
            ..Parameters::default()
        });
        let f = [0.83, 0.07, -0.05, 1.12];
        for growth in [Growth::tangential(1.3), Growth::area(1.2), Growth::tangential(0.8)] {
            check_against_differences(materials.layer.energy, growth, &f);
            check_against_differences(materials.substrate.energy, growth, &f);
        }
    }

    #[test]
    fn closed_forms_agree_with_the_differentiated_grown_energy() {
        let materials = Bilayer::new(&Parameters::default());
        let grown = Grown::ungrown(materials.substrate.energy).with_growth(Growth::area(1.15));
        let f = [0.9, 0.04, 0.02, 1.05];
        let (closed, differentiated) = (
            grown.plane_response(&f),
            crate::material::differentiated_response(&grown, &f),
        );
        for a in 0..4 {
            assert!((closed.stress[a] - differentiated.stress[a]).abs() < 1e-12);
            for b in 0..4 {
                assert!((closed.tangent[a][b] - differentiated.tangent[a][b]).abs() < 1e-11);
            }
        }
        let full = [0.9, 0.04, 0.0, 0.02, 1.05, 0.0, 0.0, 0.0, 0.97];
        let (closed, differentiated) = (
            grown.response_3d(&full),
            crate::material::differentiated_full_response(&grown, &full),
        );
        for a in 0..9 {
            assert!((closed.stress[a] - differentiated.stress[a]).abs() < 1e-12);
            for b in 0..9 {
                assert!((closed.tangent[a][b] - differentiated.tangent[a][b]).abs() < 1e-11);
            }
        }
    }

    #[test]
    fn no_growth_is_the_identity_bit_for_bit() {
        let materials = Bilayer::new(&Parameters::default());
        let f = [0.8, 0.1, -0.03, 1.2];
        let plain = materials.substrate.energy;
        let grown = Grown::ungrown(plain);
        assert_eq!(
            grown.density(&crate::material::plane_gradient(&f, 1.0)),
            plain.density(&crate::material::plane_gradient(&f, 1.0))
        );
        let (a, b) = (grown.plane_response(&f), plain.plane_response(&f));
        assert_eq!((a.energy, a.stress, a.tangent), (b.energy, b.stress, b.tangent));
    }

    #[test]
    fn a_grown_tissue_is_stress_free_at_its_growth() {
        let materials = Bilayer::new(&Parameters::default());
        for growth in [Growth::tangential(1.4), Growth::area(1.2)] {
            let grown = Grown::ungrown(materials.substrate.energy).with_growth(growth);
            let f = [growth.stretches[0], 0.0, 0.0, growth.stretches[1]];
            let (w, p) = grown.plane_stress(&f);
            assert!(w.abs() < 1e-14 && p.iter().all(|x| x.abs() < 1e-13), "{w} {p:?}");
        }
        let surface = Growth::in_surface(1.3, 1.1, false);
        let grown = Grown::ungrown(materials.substrate.energy).with_growth(surface);
        let [g1, g2, g3] = surface.stretches;
        let r = grown.response_3d(&[g1, 0.0, 0.0, 0.0, g2, 0.0, 0.0, 0.0, g3]);
        assert!(
            r.energy.abs() < 1e-14 && r.stress.iter().all(|x| x.abs() < 1e-13),
            "{r:?}"
        );
    }

    /// Growth in the surface (`g3 != 1`): the full response against central differences of
    /// `Jg W(F Fg^-1)` written out here, with fibres out of every coordinate plane; and the plane
    /// response (`F33 = 1`) is the in-plane block of the full one.
    #[test]
    fn surface_growth_stress_and_tangent_are_the_derivatives_of_the_grown_energy() {
        let materials = Bilayer::new(&Parameters {
            beta: 0.6,
            psi: 0.4,
            ..Parameters::default()
        });
        for growth in [Growth::in_surface(1.3, 1.2, false), Growth::in_surface(1.1, 0.9, true)] {
            check_full_against_differences(materials.layer.energy, growth);
            check_full_against_differences(materials.substrate.energy, growth);
        }
    }

    fn check_full_against_differences<M: StrainEnergy + Copy>(plain: M, growth: Growth) {
        let f = [0.83, 0.07, 0.02, -0.05, 1.12, 0.03, 0.01, -0.04, 0.91];
        let difference = |w: &dyn Fn(&[f64; 9]) -> f64, x: &[f64; 9], a: usize, h: f64| {
            let (mut plus, mut minus) = (*x, *x);
            plus[a] += h;
            minus[a] -= h;
            (w(&plus) - w(&minus)) / (2.0 * h)
        };
        let w = |x: &[f64; 9]| {
            let fe: [f64; 9] = std::array::from_fn(|a| x[a] / growth.stretches[a % 3]);
            plain.density(&fe) * growth.jacobian()
        };
        let grown = Grown::ungrown(plain).with_growth(growth);
        let r = crate::material::full_response(&grown, &f).unwrap();
        assert!((r.energy - w(&f)).abs() < 1e-13 * r.energy.abs().max(1.0));
        for a in 0..9 {
            let fd = difference(&w, &f, a, 1e-5);
            assert!(
                (r.stress[a] - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                "P[{a}] {} vs {fd}",
                r.stress[a]
            );
            let stress_a = |x: &[f64; 9]| difference(&w, x, a, 1e-5);
            for b in 0..9 {
                let fd = difference(&stress_a, &f, b, 1e-4);
                let exact = r.tangent[a][b];
                assert!(
                    (exact - fd).abs() < 2e-4 * (1.0 + fd.abs()),
                    "A[{a}][{b}] {exact} vs {fd}"
                );
            }
        }
        let full = grown.response_3d(&[0.83, 0.07, 0.0, -0.05, 1.12, 0.0, 0.0, 0.0, 1.0]);
        let in_plane = grown.plane_response(&[0.83, 0.07, -0.05, 1.12]);
        let (_, stress) = grown.plane_stress(&[0.83, 0.07, -0.05, 1.12]);
        let index = [0, 1, 3, 4];
        for a in 0..4 {
            assert!((in_plane.stress[a] - full.stress[index[a]]).abs() < 1e-12);
            assert!((stress[a] - full.stress[index[a]]).abs() < 1e-12);
            for b in 0..4 {
                assert!((in_plane.tangent[a][b] - full.tangent[index[a]][index[b]]).abs() < 1e-11);
            }
        }
    }
}
