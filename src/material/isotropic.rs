//! Isotropic energies in plane strain. A plane deformation `F = [[F2, 0], [0, F33]]` has the
//! invariants `t = F2 : F2`, `q = det F2` and `F33`; with them `I1 = t + F33^2`,
//! `I2 = q^2 + F33^2 t`, `J = q F33`, and the in-plane principal values of `C` are the roots
//! of `c^2 - t c + q^2` (`docs/model.md`, "Tissue laws"). An isotropic law is written once on
//! these three numbers, generic over dual numbers; its plane stress and tangent follow from
//! the two derivatives in `(t, q)` by the chain rule
//! `P = 2 W_t F + W_q cof F`,
//! `A = 4 W_tt F (x) F + 2 W_tq (F (x) cof + cof (x) F) + W_qq cof (x) cof + 2 W_t I + W_q dcof/dF`.

use super::{cofactor, Response, Tensor2};
use nalgebra::SVector;
use num_dual::{hessian, Dual2SVec64, DualNum};

/// An isotropic strain energy written on the plane invariants `(t, q, F33)`.
pub trait PlaneInvariantEnergy {
    fn invariant_density<D: DualNum<Primitive = f64> + Copy>(&self, t: D, q: D, f33: D) -> D;
}

/// `t = F2 : F2` and `q = det F2` of a plane gradient, generic over dual numbers.
pub fn plane_invariants<D: DualNum<Primitive = f64> + Copy>(f: &[D; 4]) -> (D, D) {
    (
        f[0] * f[0] + f[1] * f[1] + f[2] * f[2] + f[3] * f[3],
        f[0] * f[3] - f[1] * f[2],
    )
}

/// `W`, `P` and `A` at `F33 = 1` by the chain rule through `(t, q)`.
pub fn invariant_response<L: PlaneInvariantEnergy + ?Sized>(law: &L, f: &Tensor2) -> Response {
    let (energy, [w_t, w_q], [w_tt, w_tq, w_qq]) = invariant_derivatives(law, f);
    let cof = cofactor(f);
    let stress = std::array::from_fn(|a| 2.0 * w_t * f[a] + w_q * cof[a]);
    let mut tangent: [[f64; 4]; 4] = std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            4.0 * w_tt * f[a] * f[b] + 2.0 * w_tq * (f[a] * cof[b] + cof[a] * f[b]) + w_qq * cof[a] * cof[b]
        })
    });
    for (a, row) in tangent.iter_mut().enumerate() {
        row[a] += 2.0 * w_t;
    }
    // dcof/dF: cof = [F22, -F21, -F12, F11].
    tangent[0][3] += w_q;
    tangent[3][0] += w_q;
    tangent[1][2] -= w_q;
    tangent[2][1] -= w_q;
    Response {
        energy,
        stress,
        tangent,
    }
}

/// `W` and `P` at `F33 = 1` by the chain rule through `(t, q)`: the same hyper-dual evaluation
/// as [`invariant_response`] (so that both give the same bits), without the tangent.
pub fn invariant_stress<L: PlaneInvariantEnergy + ?Sized>(law: &L, f: &Tensor2) -> (f64, Tensor2) {
    let (energy, [w_t, w_q], _) = invariant_derivatives(law, f);
    let cof = cofactor(f);
    (energy, std::array::from_fn(|a| 2.0 * w_t * f[a] + w_q * cof[a]))
}

/// `W`, `(W_t, W_q)` and `(W_tt, W_tq, W_qq)` at `F33 = 1`.
fn invariant_derivatives<L: PlaneInvariantEnergy + ?Sized>(law: &L, f: &Tensor2) -> (f64, [f64; 2], [f64; 3]) {
    let (t, q) = plane_invariants(f);
    let (energy, g, h) = hessian(
        |x: SVector<Dual2SVec64<2>, 2>| law.invariant_density(x[0], x[1], Dual2SVec64::from_re(1.0)),
        &SVector::from([t, q]),
    );
    (energy, [g[0], g[1]], [h[(0, 0)], h[(0, 1)], h[(1, 1)]])
}

/// `c1^a + c2^a` for the in-plane principal values `c1, c2` of `C` (roots of
/// `c^2 - t c + q^2`), smooth where they coincide. With `m = t/2` and `delta^2 = m^2 - q^2`,
/// `c = m +- delta`, and the sum is even in `delta`: near coincidence it is evaluated as its
/// Taylor series in `delta^2`, `2 sum_n (a)_(2n) m^(a-2n) delta^(2n) / (2n)!`
/// (`(a)_(2n)` the falling factorial), so that no derivative divides by `delta`.
pub fn principal_power_sum<D: DualNum<Primitive = f64> + Copy>(t: D, q: D, a: f64) -> D {
    let m = t * 0.5;
    // Clamped at zero: the two roots are real for every real F2, and rounding may not cross it.
    let gap = m * m - q * q;
    let gap = if gap.re() < 0.0 { gap - gap.re() } else { gap };
    if gap.re() > SERIES_BELOW * m.re() * m.re() {
        let delta = gap.sqrt();
        return (m + delta).powf(a) + (m - delta).powf(a);
    }
    // Term n+1 over term n is (a-2n)(a-2n-1) / ((2n+1)(2n+2)) delta^2/m^2, below 1e-2 delta^2/m^2
    // times a factor that tends to 1: 80 terms bound every |a| <= 50 (|alpha| <= 100).
    let ratio = gap / (m * m);
    let mut coefficient = 1.0;
    let mut power = D::one();
    let mut sum = D::one();
    for n in 1..=80 {
        let k = 2.0 * n as f64;
        coefficient *= (a - k + 2.0) * (a - k + 1.0) / ((k - 1.0) * k);
        power *= ratio;
        let term = power * coefficient;
        sum += term;
        // The second derivative's term is n^2 / ratio^2 times larger: converge that one too.
        let n_squared = (n * n) as f64;
        if term.re().abs() * n_squared <= 1e-17 * sum.re().abs() * ratio.re() * ratio.re() && n > 2 {
            break;
        }
    }
    m.powf(a) * sum * 2.0
}

/// Below this `delta^2 / m^2`, [`principal_power_sum`] uses the series: the closed form's second
/// derivatives cancel to a relative `eps (m/delta)^2`, 1e-14 there.
const SERIES_BELOW: f64 = 1e-2;
