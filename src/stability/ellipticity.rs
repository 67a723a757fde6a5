//! Strong ellipticity: `min over unit a, n of (a x n) : A : (a x n) > 0`, over `a` with
//! `n . F^-1 a = 0` in an incompressible layer. Beyond its loss the material itself is unstable
//! and a wrinkling answer is meaningless.

use super::IncrementalModuli;
use crate::material::ellipticity::min_over_directions;

/// `min over unit a, n` of `(a x n) : A : (a x n)`: the smallest eigenvalue of the acoustic
/// tensor `Q_ik(n) = A_iJkL n_J n_L`, minimised over the direction `n` ([`min_over_directions`]).
pub fn ellipticity_margin(m: &IncrementalModuli) -> f64 {
    let smallest = |theta: f64| {
        let (c, s) = (theta.cos(), theta.sin());
        // Q_11 = A_1111 c^2 + A_1212 s^2, Q_22 = A_2121 c^2 + A_2222 s^2, Q_12 = (A_1122 + A_1221) c s.
        let q11 = m.c11 * c * c + m.c66 * s * s;
        let q22 = m.c99 * c * c + m.c22 * s * s;
        let q12 = (m.c12 + m.c69) * c * s;
        match m.incompressible_ratio {
            // The one admissible direction: a perpendicular to F^-T n ~ (c, s / r).
            Some(r) => {
                let (a1, a2) = (-s, r * c);
                (q11 * a1 * a1 + 2.0 * q12 * a1 * a2 + q22 * a2 * a2) / (a1 * a1 + a2 * a2)
            }
            None => {
                let mean = 0.5 * (q11 + q22);
                mean - (0.25 * (q11 - q22).powi(2) + q12 * q12).sqrt()
            }
        }
    };
    min_over_directions(60, smallest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotropic_linear_elasticity_margin_is_the_shear_modulus() {
        // Small-strain isotropic moduli: A_1111 = A_2222 = lambda + 2 mu, A_1122 = lambda,
        // A_1212 = A_2121 = mu, A_1221 = mu; min eigenvalue of Q is mu.
        let (lambda, mu) = (2.0, 0.7);
        let m = IncrementalModuli {
            c11: lambda + 2.0 * mu,
            c12: lambda,
            c22: lambda + 2.0 * mu,
            c66: mu,
            c69: mu,
            c99: mu,
            incompressible_ratio: None,
        };
        assert!((ellipticity_margin(&m) - mu).abs() < 1e-12);
    }
}
