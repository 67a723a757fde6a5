//! The homogeneously compressed state (paper eq. 4, Fig. 2): `x = (lambda_1 X, lambda_2 Y)` in
//! each layer with `lambda_1 = 1 - d` and `lambda_2` such that `sigma_22 = 0`; in incompressible
//! layers `lambda_2 = 1 / lambda_1` and the pressure multiplier makes `sigma_22` vanish.
//! Under a growth load ([`Bilayer::at_load`]) the ends are held, `lambda_1 = 1`, the growing
//! layers' energies are `Jg W(Fe)`, and an incompressible layer keeps `det Fe = 1`, so
//! `lambda_2 = Jg / lambda_1`.

use crate::error::{Error, Result};
use crate::material::{Bilayer, CauchyStress, Hyperelastic, StrainEnergy, Tensor2};
use crate::numerics::roots::brent;
use crate::parameters::{validate_compression, Load};
use num_dual::Dual64;
use serde::Serialize;

/// Both layers at one load: the end-shortening `d`, or under growth the strain `d = 1 - 1/g`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct HomogeneousState {
    pub d: f64,
    pub lambda1: f64,
    pub lambda2_layer: f64,
    pub lambda2_substrate: f64,
    /// The growth `g` of the layer along `X` (1 without growth).
    pub growth_layer: f64,
    /// The growth of the substrate along `X`.
    pub growth_substrate: f64,
    /// What loads the bilayer.
    pub load: Load,
}

impl HomogeneousState {
    /// How far the right end has moved in, as a fraction of the length: `d` under
    /// compression, 0 under growth (the ends are held).
    pub fn end_shortening(&self) -> f64 {
        self.load.end_shortening(self.d)
    }

    /// Deformation gradient of the layer, `diag(lambda_1, lambda_2l)`.
    pub fn layer_gradient(&self) -> Tensor2 {
        [self.lambda1, 0.0, 0.0, self.lambda2_layer]
    }

    /// Deformation gradient of the substrate, `diag(lambda_1, lambda_2s)`.
    pub fn substrate_gradient(&self) -> Tensor2 {
        [self.lambda1, 0.0, 0.0, self.lambda2_substrate]
    }
}

/// Smallest and largest transverse stretch searched for a root.
const STRETCH_RANGE: (f64, f64) = (1e-3, 1e3);

/// Solves `sigma_22(diag(lambda_1, lambda_2)) = 0` for `lambda_2` (eq. 4a or 4b).
pub fn transverse_stretch<M: Hyperelastic>(material: &M, lambda1: f64) -> Result<f64> {
    let p22 = |lambda2: f64| -> Result<f64> { Ok(material.first_piola(&[lambda1, 0.0, 0.0, lambda2])?[3]) };
    transverse_root(&format!("sigma_22 = 0 at lambda_1 = {lambda1}"), p22)
}

/// Solves `P_22(lambda_2) = 0`, hence `sigma_22 = P_22 lambda_2 / J = 0`: the root is bracketed
/// by expanding geometrically from `lambda_2 = 1` and then refined by Brent's method.
fn transverse_root(what: &str, p22: impl Fn(f64) -> Result<f64>) -> Result<f64> {
    let what = what.to_string();
    let (mut lower, mut upper) = (1.0, 1.0);
    let start = p22(1.0)?;
    if start == 0.0 {
        return Ok(1.0);
    }
    // P22 grows with lambda_2 for a stable material: expand towards the sign change. A trial
    // beyond a law's domain (Gent's limiting extensibility, where P22 grows without bound)
    // shortens the expansion: the root lies before the limit.
    let mut expand: f64 = if start < 0.0 { 1.5 } else { 1.0 / 1.5 };
    loop {
        let next = if start < 0.0 { upper * expand } else { lower * expand };
        if !(STRETCH_RANGE.0..=STRETCH_RANGE.1).contains(&next) || (expand - 1.0).abs() < 1e-12 {
            return Err(Error::NoRoot {
                what,
                lower: STRETCH_RANGE.0,
                upper: STRETCH_RANGE.1,
            });
        }
        let value = match p22(next) {
            Err(Error::BeyondExtensibility { .. }) => {
                expand = expand.sqrt();
                continue;
            }
            other => other?,
        };
        if start < 0.0 {
            (lower, upper) = (upper, next);
        } else {
            (upper, lower) = (lower, next);
        }
        if value.signum() != start.signum() {
            break;
        }
    }
    brent(&what, p22, lower, upper, 1e-15)
}

/// The homogeneous state of both layers at the load's strain `d` (eq. 4).
pub fn homogeneous_state(materials: &Bilayer, d: f64) -> Result<HomogeneousState> {
    validate_compression("d", d)?;
    let (loaded, lambda1) = materials.at_load(d);
    let (layer_growth, substrate_growth) = (loaded.layer.growth, loaded.substrate.growth);
    let (lambda2_layer, lambda2_substrate) = if materials.incompressible {
        (layer_growth.jacobian() / lambda1, substrate_growth.jacobian() / lambda1)
    } else {
        (
            transverse_stretch(&loaded.layer, lambda1)?,
            transverse_stretch(&loaded.substrate, lambda1)?,
        )
    };
    Ok(HomogeneousState {
        d,
        lambda1,
        lambda2_layer,
        lambda2_substrate,
        growth_layer: layer_growth.stretches[0],
        growth_substrate: substrate_growth.stretches[0],
        load: materials.load,
    })
}

/// Both layers under in-plane compression `d` along X and `d_3` along Z: `F = diag(lambda_1,
/// lambda_2, lambda_3)` with `lambda_1 = 1 - d`, `lambda_3 = 1 - d_3` and each layer's `lambda_2`
/// such that `sigma_22 = 0` (`Jg / (lambda_1 lambda_3)` if incompressible). `d_3 = 0` is plane
/// strain, `d_3 = d` equibiaxial compression. Under a growth load ([`Bilayer::at_biaxial_load`])
/// the sides are held (`lambda_1 = lambda_3 = 1`) and `d`, `d_3` are the growth's strains
/// `1 - 1/g`, `1 - 1/g3`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BiaxialState {
    pub d: f64,
    pub d3: f64,
    pub lambda1: f64,
    pub lambda3: f64,
    pub lambda2_layer: f64,
    pub lambda2_substrate: f64,
    /// What loads the bilayer.
    pub load: Load,
}

impl BiaxialState {
    /// How far the sides have moved in along `X` and `Z`, as fractions of the lengths: `(d,
    /// d_3)` under compression, 0 under growth (the sides are held).
    pub fn end_shortening(&self) -> [f64; 2] {
        [self.load.end_shortening(self.d), self.load.end_shortening(self.d3)]
    }

    /// The principal stretches `(lambda_1, lambda_2, lambda_3)` of the layer.
    pub fn layer_stretches(&self) -> [f64; 3] {
        [self.lambda1, self.lambda2_layer, self.lambda3]
    }

    /// The principal stretches of the substrate.
    pub fn substrate_stretches(&self) -> [f64; 3] {
        [self.lambda1, self.lambda2_substrate, self.lambda3]
    }
}

/// The biaxial homogeneous state at the load's strains `(d, d_3)`, under compression (a fixed
/// growth included) or growth.
pub fn biaxial_state(materials: &Bilayer, d: f64, d3: f64) -> Result<BiaxialState> {
    validate_compression("d", d)?;
    validate_compression("d_3", d3)?;
    let (loaded, [lambda1, lambda3]) = materials.at_biaxial_load(d, d3);
    if materials.incompressible {
        let volume = |g: crate::material::Growth| g.jacobian() / (lambda1 * lambda3);
        return Ok(BiaxialState {
            d,
            d3,
            lambda1,
            lambda3,
            lambda2_layer: volume(loaded.layer.growth),
            lambda2_substrate: volume(loaded.substrate.growth),
            load: materials.load,
        });
    }
    let solve = |material: &dyn Fn(f64) -> Result<f64>| {
        transverse_root(
            &format!("sigma_22 = 0 at lambda_1 = {lambda1}, lambda_3 = {lambda3}"),
            material,
        )
    };
    Ok(BiaxialState {
        d,
        d3,
        lambda1,
        lambda3,
        lambda2_layer: solve(&|l2| normal_stress(&loaded.layer, [lambda1, l2, lambda3]))?,
        lambda2_substrate: solve(&|l2| normal_stress(&loaded.substrate, [lambda1, l2, lambda3]))?,
        load: materials.load,
    })
}

/// `P_22 = dW/dF_22` at `diag(stretches)`, by one dual number.
pub fn normal_stress<M: StrainEnergy + ?Sized>(material: &M, [l1, l2, l3]: [f64; 3]) -> Result<f64> {
    material.admissible(&[l1, 0.0, 0.0, 0.0, l2, 0.0, 0.0, 0.0, l3])?;
    let x = Dual64::from(l2).derivative();
    let zero = Dual64::from(0.0);
    let w = material.density(&[l1.into(), zero, zero, zero, x, zero, zero, zero, l3.into()]);
    if !(w.re.is_finite() && w.eps.is_finite()) {
        return Err(Error::NonFinite(format!("the energy at diag({l1}, {l2}, {l3})")));
    }
    Ok(w.eps)
}

/// The pressure `p` (conjugate to `ln J`: `P = P_rest + p F^-T`) that makes `P_22`, hence
/// `sigma_22`, vanish at the diagonal `f` of an incompressible layer: `p = -lambda_2 P_rest,22`.
pub fn constraint_pressure<M: Hyperelastic>(rest: &M, f: &Tensor2) -> Result<f64> {
    Ok(-f[3] * rest.first_piola(f)?[3])
}

/// Cauchy stress of a layer in the homogeneous state, with the pressure of an incompressible one.
fn homogeneous_cauchy<M: Hyperelastic>(material: &M, f: &Tensor2, incompressible: bool) -> Result<CauchyStress> {
    let mut sigma = material.cauchy(f)?;
    if incompressible {
        // sigma = sigma_rest + p / J I (J = Jg under growth).
        let p = constraint_pressure(material, f)? / crate::material::jacobian(f);
        for i in [0, 2, 3] {
            sigma[i] += p;
        }
    }
    Ok(sigma)
}

/// One row of the homogeneous-state table: stretches, Jacobians and Cauchy stresses.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct HomogeneousRow {
    pub state: HomogeneousState,
    pub layer_stress: CauchyStress,
    pub substrate_stress: CauchyStress,
}

impl HomogeneousRow {
    pub fn new(materials: &Bilayer, d: f64) -> Result<Self> {
        let state = homogeneous_state(materials, d)?;
        let incompressible = materials.incompressible;
        let (loaded, _) = materials.at_load(d);
        Ok(HomogeneousRow {
            state,
            layer_stress: homogeneous_cauchy(&loaded.layer, &state.layer_gradient(), incompressible)?,
            substrate_stress: homogeneous_cauchy(&loaded.substrate, &state.substrate_gradient(), incompressible)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::Parameters;

    /// Eq. (4a) as printed but with the matrix term weighted by mu_s (`docs/model.md`, section
    /// "Corrections"): sigma_22 of the substrate, written out independently of the material module.
    fn eq_4a(p: &Parameters, l1: f64, l2: f64) -> f64 {
        let j = l1 * l2;
        let f_prime = |eta: f64| p.mu_f / 2.0 * (eta - p.lambda_f * p.lambda_f);
        let (c, s) = (p.beta.cos(), p.beta.sin());
        let matrix = p.mu_s * (2.0 / 3.0 * l2 * l2 - (l1 * l1 + 1.0) / 3.0) / j.powf(5.0 / 3.0) + p.K_s * j.ln() / j;
        p.phi_m * matrix + 4.0 * p.phi_f * s * s * l2 / l1 * f_prime(l1 * l1 * c * c + l2 * l2 * s * s)
    }

    /// Eq. (4b): sigma_22 of the layer.
    fn eq_4b(p: &Parameters, l1: f64, l2: f64) -> f64 {
        let j = l1 * l2;
        p.mu_l * (2.0 / 3.0 * l2 * l2 - (l1 * l1 + 1.0) / 3.0) / j.powf(5.0 / 3.0) + p.K_l * j.ln() / j
    }

    #[test]
    fn energy_derived_sigma22_matches_eq_4() {
        for beta in [0.0, 0.3, std::f64::consts::FRAC_PI_4, 1.2, std::f64::consts::FRAC_PI_2] {
            for lambda_f in [1.0, 0.8] {
                let p = Parameters {
                    beta,
                    lambda_f,
                    ..Parameters::default()
                };
                let m = Bilayer::new(&p);
                for (l1, l2) in [(0.9, 1.05), (0.7, 1.3), (0.5, 1.8), (1.0, 1.0)] {
                    let f = [l1, 0.0, 0.0, l2];
                    let s = m.substrate.cauchy(&f).unwrap()[2];
                    let l = m.layer.cauchy(&f).unwrap()[2];
                    assert!(
                        (s - eq_4a(&p, l1, l2)).abs() < 1e-12,
                        "4a beta={beta}: {s} vs {}",
                        eq_4a(&p, l1, l2)
                    );
                    assert!(
                        (l - eq_4b(&p, l1, l2)).abs() < 1e-12,
                        "4b: {l} vs {}",
                        eq_4b(&p, l1, l2)
                    );
                }
            }
        }
    }

    #[test]
    fn solved_state_satisfies_eq_4() {
        for beta in [0.0, 0.7, std::f64::consts::FRAC_PI_2] {
            let p = Parameters {
                beta,
                ..Parameters::default()
            };
            let m = Bilayer::new(&p);
            for d in [0.05, 0.2, 0.4, 0.6] {
                let s = homogeneous_state(&m, d).unwrap();
                assert!(eq_4a(&p, s.lambda1, s.lambda2_substrate).abs() < 1e-11);
                assert!(eq_4b(&p, s.lambda1, s.lambda2_layer).abs() < 1e-10);
                assert!(s.lambda2_substrate > 1.0 && s.lambda2_layer > 1.0);
            }
        }
    }

    #[test]
    fn zero_compression_leaves_the_reference_state() {
        let s = homogeneous_state(&Bilayer::new(&Parameters::default()), 0.0).unwrap();
        assert!((s.lambda2_layer - 1.0).abs() < 1e-14 && (s.lambda2_substrate - 1.0).abs() < 1e-14);
    }

    #[test]
    fn without_fibre_stiffness_the_substrate_is_neo_hookean() {
        // mu_f = 0 and phi_m = 1 leaves the matrix alone; with equal moduli both layers coincide.
        let p = Parameters {
            mu_f: 0.0,
            phi_m: 1.0,
            mu_l: 1.0,
            K_l: 3.0,
            beta: 0.6,
            ..Parameters::default()
        };
        let m = Bilayer::new(&p);
        for d in [0.1, 0.3, 0.5] {
            let s = homogeneous_state(&m, d).unwrap();
            assert!((s.lambda2_layer - s.lambda2_substrate).abs() < 1e-13);
        }
    }

    #[test]
    fn incompressible_limit_approaches_inverse_stretch() {
        let p = Parameters {
            K_l: 1e6,
            K_s: 1e5,
            mu_f: 0.0,
            ..Parameters::default()
        };
        let s = homogeneous_state(&Bilayer::new(&p), 0.3).unwrap();
        assert!((s.lambda2_substrate - 1.0 / 0.7).abs() < 1e-4);
        assert!((s.lambda2_layer - 1.0 / 0.7).abs() < 1e-4);
    }

    /// Incompressible: `lambda_2 = 1 / lambda_1`, `sigma_22 = 0` by the pressure, and for a
    /// neo-Hookean layer the closed form `sigma_11 = mu (lambda_1^2 - lambda_2^2)`.
    #[test]
    fn incompressible_state_is_isochoric_and_traction_free() {
        let p = Parameters {
            incompressible: true,
            ..Parameters::default()
        };
        let m = Bilayer::new(&p);
        let row = HomogeneousRow::new(&m, 0.3).unwrap();
        assert!((row.state.lambda2_layer * 0.7 - 1.0).abs() < 1e-15);
        assert!((row.state.lambda2_substrate * 0.7 - 1.0).abs() < 1e-15);
        assert!(row.layer_stress[2].abs() < 1e-13 && row.substrate_stress[2].abs() < 1e-13);
        let (l1, l2) = (0.7, 1.0 / 0.7);
        let expected = p.mu_l * (l1 * l1 - l2 * l2);
        assert!(
            (row.layer_stress[0] - expected).abs() < 1e-12,
            "{} vs {expected}",
            row.layer_stress[0]
        );
    }

    #[test]
    fn compression_out_of_range_is_rejected() {
        let m = Bilayer::new(&Parameters::default());
        assert!(homogeneous_state(&m, 1.0).is_err());
        assert!(homogeneous_state(&m, -0.1).is_err());
    }
}
