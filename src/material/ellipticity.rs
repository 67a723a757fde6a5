//! Strong ellipticity of a law at a deformation gradient: `(a x N) : A : (a x N) > 0` for every
//! unit `a` and reference direction `N` (`A = d2W/dF dF`), over `a` with `a . F^-T N = 0` where
//! the tissue is exactly incompressible (there the pressure's term vanishes). Beyond its loss
//! the continuum admits shear bands, and a finite-element answer depends on the mesh.

use super::{Tensor2, Tensor4};

/// `min over theta in [0, pi)` of `smallest(theta)`: sampled every `pi / samples`, then refined
/// by golden sections around the best sample (to `1e-5` of the sample spacing, where the
/// minimum's value is exact to about `1e-10` of its curvature).
pub fn min_over_directions(samples: usize, smallest: impl Fn(f64) -> f64) -> f64 {
    let (best_theta, best) = sampled_minimum(samples, &smallest);
    refined_minimum(samples, (best_theta, best), &smallest)
}

/// The best of `samples` directions `theta = i pi / samples`: `(theta, value)`.
fn sampled_minimum(samples: usize, smallest: &impl Fn(f64) -> f64) -> (f64, f64) {
    let step = std::f64::consts::PI / samples as f64;
    let (mut best_theta, mut best) = (0.0, f64::INFINITY);
    for i in 0..samples {
        let value = smallest(i as f64 * step);
        if value < best {
            (best_theta, best) = (i as f64 * step, value);
        }
    }
    (best_theta, best)
}

/// Golden sections within a sample spacing of the best sample `(best_theta, best)`.
fn refined_minimum(samples: usize, (best_theta, best): (f64, f64), smallest: &impl Fn(f64) -> f64) -> f64 {
    let step = std::f64::consts::PI / samples as f64;
    best.min(smallest(golden_section(smallest, best_theta, step, 25)))
}

/// The minimiser of `f` on `[centre - half_width, centre + half_width]` after `sections`
/// golden sections (each shrinks the bracket by 0.618).
pub(crate) fn golden_section(f: &impl Fn(f64) -> f64, centre: f64, half_width: f64, sections: usize) -> f64 {
    let (mut lo, mut hi) = (centre - half_width, centre + half_width);
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..sections {
        let (x1, x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        if f(x1) < f(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    0.5 * (lo + hi)
}

/// Directions sampled by [`referential_margin`] before the refinement (every 15 degrees).
const DIRECTIONS: usize = 12;

/// The margin `min (a x N) : A : (a x N)` over unit `a` and `N = (cos theta, sin theta)` of the
/// referential tangent `a_tensor` (`A[2i+J][2k+L]`) at `f`: the smallest eigenvalue of the
/// acoustic tensor `Q_ik(N) = A_iJkL N_J N_L`, or, if `incompressible`, `Q` on the one
/// admissible `a`, perpendicular to `F^-T N`. In units of the moduli.
pub fn referential_margin(a_tensor: &Tensor4, f: &Tensor2, incompressible: bool) -> f64 {
    // Q(N) = c^2 Q_XX + 2 c s Q_XY + s^2 Q_YY, each (Q_JL)_ik = A_iJkL symmetrised in (i, k).
    let part = |j: usize, l: usize| {
        let q = |i: usize, k: usize| 0.5 * (a_tensor[2 * i + j][2 * k + l] + a_tensor[2 * i + l][2 * k + j]);
        [q(0, 0), 0.5 * (q(0, 1) + q(1, 0)), q(1, 1)]
    };
    let (xx, xy, yy) = (part(0, 0), part(0, 1), part(1, 1));
    let smallest = |theta: f64| {
        let n = [theta.cos(), theta.sin()];
        let q = |m: usize| n[0] * n[0] * xx[m] + 2.0 * n[0] * n[1] * xy[m] + n[1] * n[1] * yy[m];
        let (q11, q12, q22) = (q(0), q(1), q(2));
        if incompressible {
            // F^-T N (up to 1/J) = (F22 N1 - F21 N2, -F12 N1 + F11 N2); a is perpendicular to it.
            let m = [f[3] * n[0] - f[2] * n[1], -f[1] * n[0] + f[0] * n[1]];
            let a = [-m[1], m[0]];
            (q11 * a[0] * a[0] + 2.0 * q12 * a[0] * a[1] + q22 * a[1] * a[1]) / (a[0] * a[0] + a[1] * a[1])
        } else {
            0.5 * (q11 + q22) - (0.25 * (q11 - q22).powi(2) + q12 * q12).sqrt()
        }
    };
    // Refined only where the sampled minimum is below a quarter of the stiffness scale: the
    // sampling overestimates a minimum by at most about 2 % of that scale, so every margin
    // near zero (and its sign) is exact, and a large one is within about 2 %.
    let sampled = sampled_minimum(DIRECTIONS, &smallest);
    let scale = 0.5 * (xx[0] + xx[2]).abs().max((yy[0] + yy[2]).abs());
    match sampled.1 < REFINE_BELOW * scale {
        true => refined_minimum(DIRECTIONS, sampled, &smallest),
        false => sampled.1,
    }
}

/// Fraction of the stiffness scale below which a sampled margin is refined.
const REFINE_BELOW: f64 = 0.25;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Hyperelastic, NeoHookean};

    /// At `F = I` a neo-Hookean solid's tangent is isotropic linear elasticity's,
    /// `A_iJkL = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk)` with `lambda = K - 2 mu / 3`
    /// (plane strain of the 3D law): `Q(N) = mu I + (lambda + mu) N N`, whose smallest
    /// eigenvalue is `mu` in every direction; under the incompressibility constraint `a` is
    /// perpendicular to `N`, where `Q a = mu a` too.
    #[test]
    fn the_margin_of_an_unstrained_neo_hookean_solid_is_its_shear_modulus() {
        let solid = NeoHookean { mu: 1.7, bulk: 40.0 };
        let identity = [1.0, 0.0, 0.0, 1.0];
        let tangent = solid.response(&identity).unwrap().tangent;
        for incompressible in [false, true] {
            let margin = referential_margin(&tangent, &identity, incompressible);
            assert!((margin - 1.7).abs() < 1e-10, "{incompressible}: {margin}");
        }
    }

    /// The margin is a minimum over directions, so at most `A_1111` (`a = N = e1`): where a
    /// stiff fibre family along `X` compressed to `lambda = 0.5` makes `A_1111` negative, the
    /// margin is negative too; stretched, it stays positive.
    #[test]
    fn compressed_stiff_fibres_lose_strong_ellipticity() {
        use crate::material::FibreFamily;
        let fibre = FibreFamily {
            stiffness: 200.0,
            prestretch: 1.0,
            direction: [1.0, 0.0, 0.0],
            tension_only: false,
        };
        let matrix = NeoHookean { mu: 1.0, bulk: 3.0 };
        let margin_at = |stretch: f64| {
            let f = [stretch, 0.0, 0.0, 1.0];
            let mut tangent = matrix.response(&f).unwrap().tangent;
            let t = fibre.response(&f).unwrap().tangent;
            for (row, extra) in tangent.iter_mut().zip(t) {
                for (x, y) in row.iter_mut().zip(extra) {
                    *x += y;
                }
            }
            (referential_margin(&tangent, &f, false), tangent[0][0])
        };
        let (compressed, a1111) = margin_at(0.5);
        assert!(a1111 < 0.0, "A_1111 = {a1111}");
        assert!(compressed < 0.0, "{compressed}");
        assert!(
            compressed <= a1111 + 1e-12,
            "the margin is at most A_1111: {compressed} > {a1111}"
        );
        assert!(margin_at(1.2).0 > 0.0);
    }
}
