//! Gap functions and the augmented-Lagrangian contact energy of one pair, written once,
//! generic over dual numbers, and differentiated by `num_dual::hessian`.
//!
//! A pair's normal gap `g` is positive when open and negative when penetrating. With the
//! multiplier estimate `lambda >= 0` (a nominal pressure: force per reference length), the
//! penalty `eps` and the slave node's reference tributary length `w`, the pair's pressure is
//! `p = P(lambda - eps g)` with `P(s) = <s>_+` (Simo & Laursen 1992) smoothed over
//! `|s| < b`: `P = (s + b)^2 / (4 b)` there, so that the energy `psi = w / eps Phi(s)`,
//! `Phi' = P`, is twice continuously differentiable and Newton's method meets no kink when a
//! pair opens or closes. `b = eps delta / 2` spreads the switch over a gap `delta` far below
//! the tolerance. Uzawa's update is `lambda <- p`.

use super::super::added::Block;
use nalgebra::SVector;
use num_dual::{hessian, Dual2SVec64, DualNum};

/// Gap of point `x` to the plane `{n . x = c}` (`n` a unit normal towards the open side).
pub fn plane_gap<D: DualNum<Primitive = f64> + Copy>(x: [D; 2], normal: [f64; 2], offset: f64) -> D {
    x[0] * normal[0] + x[1] * normal[1] - offset
}

/// Signed distance of the slave `s` to the line through the master segment `a -> b`, measured
/// along the segment's outward normal `perp(b - a) / |b - a|`, `perp(t) = (-t_y, t_x)` (the
/// surface runs left to right with the body below it, so the normal points out of the body).
pub fn segment_gap<D: DualNum<Primitive = f64> + Copy>(s: [D; 2], a: [D; 2], b: [D; 2]) -> D {
    let t = [b[0] - a[0], b[1] - a[1]];
    let length = (t[0] * t[0] + t[1] * t[1]).sqrt();
    ((s[1] - a[1]) * t[0] - (s[0] - a[0]) * t[1]) / length
}

/// Where the slave projects on the master segment: `xi = (s - a).(b - a) / |b - a|^2`.
pub fn projection(s: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let t = [b[0] - a[0], b[1] - a[1]];
    ((s[0] - a[0]) * t[0] + (s[1] - a[1]) * t[1]) / (t[0] * t[0] + t[1] * t[1])
}

/// Width `delta` of the gaps over which a pair switches on (far below the tolerance `1e-3 H`).
pub const SWITCH_GAP: f64 = 1e-4;

/// `Phi(s)`, the integral of the smoothed ramp `P` with half-width `b`.
fn ramp_integral<D: DualNum<Primitive = f64> + Copy>(s: D, b: f64) -> D {
    if s.re() >= b {
        s * s * 0.5 + b * b / 6.0
    } else if s.re() > -b {
        let t = s + b;
        t * t * t / (12.0 * b)
    } else {
        D::zero()
    }
}

/// The half-width `b = eps delta / 2` of the switch in the pressure argument `s`.
fn switch_half_width(penalty: f64) -> f64 {
    0.5 * penalty * SWITCH_GAP
}

/// The pair energy `psi(g) = w / eps Phi(lambda - eps g)` (module docs).
pub fn pair_energy<D: DualNum<Primitive = f64> + Copy>(gap: D, multiplier: f64, penalty: f64, weight: f64) -> D {
    ramp_integral(-gap * penalty + multiplier, switch_half_width(penalty)) * (weight / penalty)
}

/// The pressure argument `s = lambda - eps g`.
pub fn pressure_argument(gap: f64, multiplier: f64, penalty: f64) -> f64 {
    multiplier - penalty * gap
}

/// Contact pressure `P(lambda - eps g)`.
pub fn pressure(gap: f64, multiplier: f64, penalty: f64) -> f64 {
    let (s, b) = (pressure_argument(gap, multiplier, penalty), switch_half_width(penalty));
    if s >= b {
        s
    } else if s > -b {
        (s + b) * (s + b) / (4.0 * b)
    } else {
        0.0
    }
}

/// Energy, gradient and Hessian of `energy` of `N` coordinates at `x`, as a [`Block`].
pub fn differentiate<const N: usize>(
    energy: impl Fn(&[Dual2SVec64<N>; N]) -> Dual2SVec64<N>,
    x: [f64; N],
    with_tangent: bool,
) -> Block {
    let (e, g, h) = hessian(
        |v: SVector<Dual2SVec64<N>, N>| energy(&std::array::from_fn(|i| v[i])),
        &SVector::from(x),
    );
    Block {
        energy: e,
        gradient: g.iter().copied().collect(),
        hessian: if with_tangent {
            (0..N * N).map(|k| h[(k / N, k % N)]).collect()
        } else {
            Vec::new()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_gap_is_the_signed_distance_to_the_line() {
        let (a, b) = ([0.0, 0.0], [2.0, 0.0]);
        assert_eq!(segment_gap([0.5, 0.3], a, b), 0.3);
        assert_eq!(segment_gap([1.5, -0.2], a, b), -0.2);
        // A segment running down-right: its outward normal points up-right.
        let g = segment_gap([1.0, 1.0], [0.0, 0.0], [1.0, -1.0]);
        assert!((g - 2.0f64.sqrt()).abs() < 1e-15);
        assert_eq!(projection([0.5, 0.3], a, b), 0.25);
    }

    #[test]
    fn pair_energy_gives_the_penalty_force_and_stiffness() {
        // Slave at gap g = -0.01 against the plane x = 0: force w eps |g| outwards, stiffness w eps.
        let (eps, w, g) = (100.0, 0.3, -0.01);
        let block = differentiate(
            |x| pair_energy(plane_gap([x[0], x[1]], [1.0, 0.0], 0.0), 0.0, eps, w),
            [g, 0.5],
            true,
        );
        assert!((block.gradient[0] + w * eps * 0.01).abs() < 1e-14);
        assert_eq!(block.gradient[1], 0.0);
        assert!((block.hessian[0] - w * eps).abs() < 1e-12);
        let b = 0.5 * eps * SWITCH_GAP;
        assert!((block.energy - 0.5 * w * eps * g * g - w * b * b / (6.0 * eps)).abs() < 1e-15);
        // Open and without multiplier: nothing.
        let open = differentiate(|x| pair_energy(x[0], 0.0, eps, w), [0.01], true);
        assert_eq!((open.energy, open.gradient[0], open.hessian[0]), (0.0, 0.0, 0.0));
        assert_eq!(pressure(g, 0.5, eps), 1.5);
    }

    #[test]
    fn the_switch_is_smooth_and_integrates_to_the_energy() {
        let (eps, w, lambda) = (1e4, 0.2, 0.0);
        let b = 0.5 * eps * SWITCH_GAP;
        // Across the switch (gaps from -2 delta to 2 delta) the force is -w P and its slope w eps P'.
        for k in -20..=20 {
            let g = k as f64 * 0.1 * SWITCH_GAP;
            let block = differentiate(|x| pair_energy(x[0], lambda, eps, w), [g], true);
            assert!((block.gradient[0] + w * pressure(g, lambda, eps)).abs() < 1e-12);
            let h = 1e-9;
            let slope = -w * (pressure(g + h, lambda, eps) - pressure(g - h, lambda, eps)) / (2.0 * h);
            // (P' has a kink at the ends of the switch: central differences straddling it err by ~eps h / b.)
            assert!(
                (block.hessian[0] - slope).abs() < 1e-4 * w * eps,
                "{g}: {} vs {slope}",
                block.hessian[0]
            );
        }
        assert_eq!(pressure(-SWITCH_GAP / 2.0, 0.0, eps), b);
        assert_eq!(pressure(SWITCH_GAP / 2.0, 0.0, eps), 0.0);
    }
}
