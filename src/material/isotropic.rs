//! Isotropic energies, written once on the invariants of `C = F^T F`, for a plane `F` and for
//! a full 3x3 `F` alike (`docs/model.md`, 3.1).
//!
//! A law sees [`Invariants`]: `I1`, `I2`, `J` and, for Ogden, the sums `sum_i lambda_i^a` of
//! the principal stretches to a power. A plane deformation `F = [[F2, 0], [0, F33]]` has them
//! from `t = F2 : F2`, `q = det F2` and `F33`: `I1 = t + F33^2`, `I2 = q^2 + F33^2 t`,
//! `J = q F33`, and its in-plane principal values of `C` are the roots of `c^2 - t c + q^2`.
//! In plane strain the stress and tangent follow from two derivatives in `(t, q)` by the chain
//! rule (fast, as the finite elements need):
//! `P = 2 W_t F + W_q cof F`,
//! `A = 4 W_tt F (x) F + 2 W_tq (F (x) cof + cof (x) F) + W_qq cof (x) cof + 2 W_t I + W_q dcof/dF`.

use super::{cofactor, Response, Tensor2};
use nalgebra::{Matrix3, SVector, SymmetricEigen};
use num_dual::{hessian, Dual2SVec64, DualNum};

/// What an isotropic energy depends on at one deformation (generic over dual numbers).
pub struct Invariants<D> {
    pub i1: D,
    pub i2: D,
    pub j: D,
    principal: Principal<D>,
}

/// How the principal stretches are reached.
enum Principal<D> {
    /// `F = [[F2, 0], [0, F33]]`: the in-plane pair from `(t, q)`, and `F33`.
    Plane { t: D, q: D, f33: D },
    /// A full `F`: `C` (symmetric, row-major).
    Full { c: [[D; 3]; 3] },
}

impl<D: DualNum<Primitive = f64> + Copy> Invariants<D> {
    /// The invariants of a plane deformation with `t = F2 : F2`, `q = det F2` and `F33`.
    pub fn plane(t: D, q: D, f33: D) -> Self {
        let f33_squared = f33 * f33;
        Invariants {
            i1: t + f33_squared,
            i2: q * q + f33_squared * t,
            j: q * f33,
            principal: Principal::Plane { t, q, f33 },
        }
    }

    /// The invariants of a full 3x3 `F` (row-major, `F_iJ = f[3 i + J]`).
    pub fn of_gradient(f: &[D; 9]) -> Self {
        let c: [[D; 3]; 3] = std::array::from_fn(|a| {
            std::array::from_fn(|b| (0..3).fold(D::zero(), |s, i| s + f[3 * i + a] * f[3 * i + b]))
        });
        let i1 = c[0][0] + c[1][1] + c[2][2];
        let trace_c_squared = (0..3).fold(D::zero(), |s, a| (0..3).fold(s, |s, b| s + c[a][b] * c[b][a]));
        let j = f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6])
            + f[2] * (f[3] * f[7] - f[4] * f[6]);
        Invariants {
            i1,
            i2: (i1 * i1 - trace_c_squared) * 0.5,
            j,
            principal: Principal::Full { c },
        }
    }

    /// `sum_i lambda_i^a` over the three principal stretches, smooth where they coincide.
    pub fn stretch_power_sum(&self, a: f64) -> D {
        match &self.principal {
            Principal::Plane { t, q, f33 } => principal_power_sum(*t, *q, 0.5 * a) + f33.powf(a),
            Principal::Full { c } => full_power_sum(c, self, 0.5 * a),
        }
    }
}

/// An isotropic strain energy written on [`Invariants`].
pub trait IsotropicEnergy {
    fn isotropic_density<D: DualNum<Primitive = f64> + Copy>(&self, inv: &Invariants<D>) -> D;

    /// An error at a plane gradient outside the law's domain ([`super::StrainEnergy::admissible`]).
    fn admissible(&self, _f: &[f64; 9]) -> crate::error::Result<()> {
        Ok(())
    }

    /// Whether [`IsotropicEnergy::admissible`] can fail ([`super::StrainEnergy::bounded_domain`]).
    fn bounded_domain(&self) -> bool {
        false
    }
}

/// `StrainEnergy` of an [`IsotropicEnergy`]: the density from the full gradient's invariants,
/// the plane stress and tangent by the chain rule through `(t, q)`.
macro_rules! strain_energy_by_invariants {
    ($law:ty) => {
        impl $crate::material::StrainEnergy for $law {
            fn density<D: num_dual::DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
                use $crate::material::isotropic::{Invariants, IsotropicEnergy};
                self.isotropic_density(&Invariants::of_gradient(f))
            }

            fn plane_response(&self, f: &$crate::material::Tensor2) -> $crate::material::Response {
                $crate::material::isotropic::invariant_response(self, f)
            }

            fn plane_stress(&self, f: &$crate::material::Tensor2) -> (f64, $crate::material::Tensor2) {
                $crate::material::isotropic::invariant_stress(self, f)
            }

            fn admissible(&self, f: &[f64; 9]) -> $crate::error::Result<()> {
                $crate::material::isotropic::IsotropicEnergy::admissible(self, f)
            }

            fn bounded_domain(&self) -> bool {
                $crate::material::isotropic::IsotropicEnergy::bounded_domain(self)
            }
        }
    };
}
pub(crate) use strain_energy_by_invariants;

/// `t = F2 : F2` and `q = det F2` of a plane gradient, generic over dual numbers.
pub fn plane_invariants<D: DualNum<Primitive = f64> + Copy>(f: &[D; 4]) -> (D, D) {
    (
        f[0] * f[0] + f[1] * f[1] + f[2] * f[2] + f[3] * f[3],
        f[0] * f[3] - f[1] * f[2],
    )
}

/// `W`, `P` and `A` at `F33 = 1` by the chain rule through `(t, q)`.
pub fn invariant_response<L: IsotropicEnergy + ?Sized>(law: &L, f: &Tensor2) -> Response {
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
pub fn invariant_stress<L: IsotropicEnergy + ?Sized>(law: &L, f: &Tensor2) -> (f64, Tensor2) {
    let (energy, [w_t, w_q], _) = invariant_derivatives(law, f);
    let cof = cofactor(f);
    (energy, std::array::from_fn(|a| 2.0 * w_t * f[a] + w_q * cof[a]))
}

/// `W`, `(W_t, W_q)` and `(W_tt, W_tq, W_qq)` at `F33 = 1`.
fn invariant_derivatives<L: IsotropicEnergy + ?Sized>(law: &L, f: &Tensor2) -> (f64, [f64; 2], [f64; 3]) {
    let (t, q) = plane_invariants(f);
    let (energy, g, h) = hessian(
        |x: SVector<Dual2SVec64<2>, 2>| {
            law.isotropic_density(&Invariants::plane(x[0], x[1], Dual2SVec64::from_re(1.0)))
        },
        &SVector::from([t, q]),
    );
    (energy, [g[0], g[1]], [h[(0, 0)], h[(0, 1)], h[(1, 1)]])
}

/// `c1^b + c2^b` for the roots `c1, c2` of `c^2 - t c + q^2` (the in-plane principal values of
/// `C`), smooth where they coincide. With `m = t/2` and `delta^2 = m^2 - q^2`, `c = m +- delta`,
/// and the sum is even in `delta`: near coincidence it is evaluated as its Taylor series in
/// `delta^2`, `2 sum_n (b)_(2n) m^(b-2n) delta^(2n) / (2n)!` (`(b)_(2n)` the falling
/// factorial), so that no derivative divides by `delta`.
pub fn principal_power_sum<D: DualNum<Primitive = f64> + Copy>(t: D, q: D, b: f64) -> D {
    let m = t * 0.5;
    // Clamped at zero: the two roots are real for every real F2, and rounding may not cross it.
    let gap = m * m - q * q;
    let gap = if gap.re() < 0.0 { gap - gap.re() } else { gap };
    if gap.re() > SERIES_BELOW * m.re() * m.re() {
        let delta = gap.sqrt();
        return (m + delta).powf(b) + (m - delta).powf(b);
    }
    // Term n+1 over term n is (b-2n)(b-2n-1) / ((2n+1)(2n+2)) delta^2/m^2, below 1e-2 delta^2/m^2
    // times a factor that tends to 1: 80 terms bound every |b| <= 50 (|alpha| <= 100).
    let ratio = gap / (m * m);
    let mut coefficient = 1.0;
    let mut power = D::one();
    let mut sum = D::one();
    for n in 1..=80 {
        let k = 2.0 * n as f64;
        coefficient *= (b - k + 2.0) * (b - k + 1.0) / ((k - 1.0) * k);
        power *= ratio;
        let term = power * coefficient;
        sum += term;
        // The second derivative's term is n^2 / ratio^2 times larger: converge that one too.
        let n_squared = (n * n) as f64;
        if term.re().abs() * n_squared <= 1e-17 * sum.re().abs() * ratio.re() * ratio.re() && n > 2 {
            break;
        }
    }
    m.powf(b) * sum * 2.0
}

/// Below this `delta^2 / m^2`, [`principal_power_sum`] uses the series: the closed form's second
/// derivatives cancel to a relative `eps (m/delta)^2`, 1e-14 there.
const SERIES_BELOW: f64 = 1e-2;

/// `c1^b + c2^b + c3^b` for the eigenvalues of a full `C`, smooth where they coincide.
/// * All three nearly equal (spread below `0.05 / max(|b|, 1)` of their mean `m`): the binomial
///   series `m^b sum_n (b choose n) tr(E^n)`, `E = C/m - I`.
/// * Otherwise one eigenvalue stands apart from the other two: it is a simple root of the
///   characteristic cubic, refined in dual numbers by Newton's method (two steps carry the
///   second derivatives), and the other two are the roots of `c^2 - s c + p` with
///   `s = I1 - c_apart`, `p = I3 / c_apart`, summed by [`principal_power_sum`].
fn full_power_sum<D: DualNum<Primitive = f64> + Copy>(c: &[[D; 3]; 3], inv: &Invariants<D>, b: f64) -> D {
    // The eigenvalues of the real part, only to choose the evaluation (only Ogden needs them).
    let mut values: [f64; 3] = SymmetricEigen::new(Matrix3::from_fn(|a, k| c[a][k].re()))
        .eigenvalues
        .into();
    values.sort_by(f64::total_cmp);
    let mean = values.iter().sum::<f64>() / 3.0;
    let spread = values.iter().fold(0.0f64, |s, v| s.max((v - mean).abs())) / mean;
    let i3 = inv.j * inv.j;
    if spread * b.abs().max(1.0) < 0.05 {
        let m = inv.i1 / 3.0;
        let e: [[D; 3]; 3] =
            std::array::from_fn(|a| std::array::from_fn(|k| c[a][k] / m - if a == k { 1.0 } else { 0.0 }));
        let mut power = e;
        let mut coefficient = b;
        let mut sum = D::from(3.0);
        for n in 1..=60 {
            let trace = power[0][0] + power[1][1] + power[2][2];
            sum += trace * coefficient;
            // |tr E^n| <= 3 spread^n, and its second derivatives n^2 spread^(n-2) times more.
            if n >= 3 && coefficient.abs() * spread.powi(n - 2) * (n * n) as f64 <= 1e-17 {
                break;
            }
            coefficient *= (b - n as f64) / (n as f64 + 1.0);
            power = std::array::from_fn(|a| {
                std::array::from_fn(|k| (0..3).fold(D::zero(), |s, l| s + power[a][l] * e[l][k]))
            });
        }
        return m.powf(b) * sum;
    }
    // The eigenvalue farthest from its neighbour stands apart.
    let apart_value = if values[1] - values[0] < values[2] - values[1] {
        values[2]
    } else {
        values[0]
    };
    let cubic = |x: D| ((x - inv.i1) * x + inv.i2) * x - i3;
    let slope = |x: D| (x * 3.0 - inv.i1 * 2.0) * x + inv.i2;
    let mut apart = D::from(apart_value);
    for _ in 0..3 {
        apart -= cubic(apart) / slope(apart);
    }
    let (s, p) = (inv.i1 - apart, i3 / apart);
    principal_power_sum(s, p.sqrt(), b) + apart.powf(b)
}
