//! The 3D incremental moduli of a layer at its homogeneous state `F = diag(lambda_1, lambda_2,
//! lambda_3)` and the 6x6 Stroh matrix of a mode `U(Y) exp(i k (cos theta X + sin theta Z))`.

use crate::error::Result;
use crate::material::ellipticity::golden_section;
use crate::material::{full_response, StrainEnergy};
use nalgebra::{Complex, Matrix3, Matrix6, SMatrix, SVector, Vector3};

/// `A_iJkL = d2W / dF_iJ dF_kL` at `[3 i + J][3 k + L]` (X = 0, Y = 1, Z = 2).
pub type FullTangent = [[f64; 9]; 9];

/// The moduli of one layer at a diagonal state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceModuli {
    /// The tangent; for an incompressible layer that of the Lagrangian `W_rest + p ln J`.
    pub tangent: FullTangent,
    /// `(lambda_1, lambda_2, lambda_3)`.
    pub stretches: [f64; 3],
    /// Increments keep `J = 1` to first order: `tr(F^-1 Grad u) = 0`.
    pub incompressible: bool,
}

type C = Complex<f64>;

impl SurfaceModuli {
    /// Moduli of `material` at `diag(stretches)`.
    pub fn at<M: StrainEnergy + ?Sized>(material: &M, stretches: [f64; 3]) -> Result<Self> {
        Ok(SurfaceModuli {
            tangent: full_response(material, &diagonal(stretches))?.tangent,
            stretches,
            incompressible: false,
        })
    }

    /// Moduli of an incompressible layer (`rest` its energy without bulk term) at `diag(stretches)`
    /// with `J = 1` and pressure `p` conjugate to `ln J`: `A = A_rest + p d(F^-T)/dF`, where
    /// `d(F^-T)_iJ / dF_kL = -(F^-1)_Jk (F^-1)_Li`, nonzero at a diagonal `F` for `J = k`, `L = i`.
    pub fn incompressible<M: StrainEnergy + ?Sized>(rest: &M, stretches: [f64; 3], p: f64) -> Result<Self> {
        let mut tangent = full_response(rest, &diagonal(stretches))?.tangent;
        for i in 0..3 {
            for k in 0..3 {
                tangent[3 * i + k][3 * k + i] -= p / (stretches[i] * stretches[k]);
            }
        }
        Ok(SurfaceModuli {
            tangent,
            stretches,
            incompressible: true,
        })
    }

    /// `sum A_iJkL a_J b_L` over the directions `a`, `b` (3-vectors): the 3x3 matrix in `(i, k)`.
    pub fn contracted(&self, a: [f64; 3], b: [f64; 3]) -> Matrix3<f64> {
        Matrix3::from_fn(|i, k| {
            let mut sum = 0.0;
            for (jj, aj) in a.iter().enumerate() {
                for (ll, bl) in b.iter().enumerate() {
                    sum += self.tangent[3 * i + jj][3 * k + ll] * aj * bl;
                }
            }
            sum
        })
    }

    /// The Stroh matrix `M` of `y' = k M y` for `y = (U, t / k)`, `t_i` the incremental nominal
    /// traction on planes `Y = const` of the mode `U(Y) exp(i k n . X)`, `n = (cos theta, 0,
    /// sin theta)`. With `Q = A(n, n)`, `R = A(n, e_Y)`, `T = A(e_Y, e_Y)` ([`Self::contracted`]):
    /// `t = T U' + i k R^T U` and `t' = -i k R U' + k^2 Q U` (equilibrium). An incompressible
    /// layer adds the constraint `U_Y' = -i k lambda_2 (n_1 U_1 / lambda_1 + n_3 U_3 / lambda_3)`
    /// and the incremental pressure `q`, which adds `q / lambda_i` to `S_ii`: `q / lambda_2` to
    /// `t_Y` and `-i k q n_i / lambda_i` to `t_i'`. `(U', q)` is solved from the traction's
    /// definition (and the constraint) at `k = 1`; `M` does not depend on `k`.
    pub fn stroh_matrix(&self, theta: f64) -> Matrix6<C> {
        let n = [theta.cos(), 0.0, theta.sin()];
        let e_y = [0.0, 1.0, 0.0];
        let (q, r, t) = (
            self.contracted(n, n).map(C::from),
            self.contracted(n, e_y).map(C::from),
            self.contracted(e_y, e_y).map(C::from),
        );
        let i = C::i();
        // Unknowns x = (U', q); rows: the three traction definitions, then the constraint.
        let mut lhs = SMatrix::<C, 4, 4>::zeros();
        let mut rhs = SMatrix::<C, 4, 6>::zeros();
        for row in 0..3 {
            for col in 0..3 {
                lhs[(row, col)] = t[(row, col)];
                // t / k = s:  T U' + q e_Y / lambda_2 = s - i R^T U.
                rhs[(row, col)] = -i * r[(col, row)];
            }
            rhs[(row, 3 + row)] = C::from(1.0);
        }
        let lambda = self.stretches;
        if self.incompressible {
            lhs[(1, 3)] = C::from(1.0 / lambda[1]);
            lhs[(3, 1)] = C::from(1.0);
            rhs[(3, 0)] = -i * lambda[1] * n[0] / lambda[0];
            rhs[(3, 2)] = -i * lambda[1] * n[2] / lambda[2];
        } else {
            lhs[(3, 3)] = C::from(1.0);
        }
        let solved = lhs.try_inverse().expect("an elliptic layer has an invertible T") * rhs;
        let mut m = Matrix6::<C>::zeros();
        for col in 0..6 {
            let u_prime = SVector::<C, 3>::new(solved[(0, col)], solved[(1, col)], solved[(2, col)]);
            let pressure = solved[(3, col)];
            let u = SVector::<C, 3>::from_fn(|k, _| if k == col { C::from(1.0) } else { C::from(0.0) });
            let s_prime = -(r * u_prime) * i + q * u
                - SVector::<C, 3>::new(C::from(n[0] / lambda[0]), C::from(0.0), C::from(n[2] / lambda[2]))
                    * (i * pressure);
            for row in 0..3 {
                m[(row, col)] = u_prime[row];
                m[(3 + row, col)] = s_prime[row];
            }
        }
        m
    }
}

/// The smallest eigenvalue of a symmetric 3x3 matrix: the least diagonal entry of a diagonal
/// one (an acoustic tensor along a principal axis); otherwise by the trigonometric solution of
/// its characteristic cubic (Smith 1961): with `q = tr/3`, `p = |A - q I|_F / sqrt 6` and
/// `B = (A - q I) / p`, the eigenvalues are `q + 2 p cos(phi + 2 pi j / 3)`, `cos 3 phi = det B / 2`.
/// Near a double eigenvalue (`|det B / 2|` near 1) the arccosine loses half the digits of the
/// pair, but not of the simple root, whose cosine is stationary there. If the pair is the
/// smaller, it is the spectrum of `A` on the plane normal to the simple root's eigenvector
/// (Eberly's deflation), a 2x2 problem without cancellation.
pub(super) fn smallest_eigenvalue(a: &Matrix3<f64>) -> f64 {
    if a[(0, 1)] == 0.0 && a[(0, 2)] == 0.0 && a[(1, 2)] == 0.0 {
        return a[(0, 0)].min(a[(1, 1)]).min(a[(2, 2)]);
    }
    let q = a.trace() / 3.0;
    let shifted = a - Matrix3::identity() * q;
    let p = (shifted.norm_squared() / 6.0).sqrt();
    let half_det = ((shifted / p).determinant() / 2.0).clamp(-1.0, 1.0);
    let phi = half_det.acos() / 3.0;
    let third = 2.0 * std::f64::consts::PI / 3.0;
    if half_det < 1.0 - 1e-6 {
        return q + 2.0 * p * (phi + third).cos();
    }
    // The pair is the smaller: deflate the largest, simple root.
    let largest = q + 2.0 * p * phi.cos();
    let rows = a - Matrix3::identity() * largest;
    let (r0, r1, r2) = (
        rows.row(0).transpose(),
        rows.row(1).transpose(),
        rows.row(2).transpose(),
    );
    let candidates = [r0.cross(&r1), r0.cross(&r2), r1.cross(&r2)];
    let v = candidates
        .iter()
        .max_by(|x, y| x.norm_squared().total_cmp(&y.norm_squared()))
        .expect("three candidates")
        .normalize();
    smallest_on_plane(a, &v)
}

/// The smaller eigenvalue of the symmetric `a` restricted to the plane normal to the unit `v`.
fn smallest_on_plane(a: &Matrix3<f64>, v: &Vector3<f64>) -> f64 {
    let helper = if v[0].abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    let u = v.cross(&helper).normalize();
    let w = v.cross(&u);
    let (uu, uw, ww) = ((a * u).dot(&u), (a * u).dot(&w), (a * w).dot(&w));
    0.5 * (uu + ww) - (0.25 * (uu - ww).powi(2) + uw * uw).sqrt()
}

/// Directions sampled by the ellipticity margin: every `pi / MARGIN_STEPS` in the polar angle
/// from `Y` and in the azimuth over `[0, pi)` (with `-n` this covers the sphere), each pole once.
const MARGIN_STEPS: usize = 12;

/// The sampled unit directions `n`, with their `(polar, azimuth)`.
fn margin_directions() -> &'static [([f64; 3], f64, f64)] {
    static DIRECTIONS: std::sync::OnceLock<Vec<([f64; 3], f64, f64)>> = std::sync::OnceLock::new();
    DIRECTIONS.get_or_init(|| {
        let step = std::f64::consts::PI / MARGIN_STEPS as f64;
        let mut list = vec![([0.0, 1.0, 0.0], 0.0, 0.0)];
        for i in 1..MARGIN_STEPS {
            for j in 0..MARGIN_STEPS {
                let (polar, azimuth) = (i as f64 * step, j as f64 * step);
                list.push((surface_direction(polar, azimuth), polar, azimuth));
            }
        }
        list
    })
}

/// The unit vector at `polar` from `Y` and `azimuth` from `X` towards `Z`.
fn surface_direction(polar: f64, azimuth: f64) -> [f64; 3] {
    [polar.sin() * azimuth.cos(), polar.cos(), polar.sin() * azimuth.sin()]
}

/// The unit vector along axis `i`.
fn e(i: usize) -> [f64; 3] {
    std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 })
}

/// `diag(stretches)` as a full gradient (row-major).
pub fn diagonal([l1, l2, l3]: [f64; 3]) -> [f64; 9] {
    [l1, 0.0, 0.0, 0.0, l2, 0.0, 0.0, 0.0, l3]
}

impl SurfaceModuli {
    /// Strong ellipticity in 3D: `min over unit a, n` of `(a x n) : A : (a x n)`, the smallest
    /// eigenvalue of the acoustic tensor `Q(n) = A(n, n)` over the unit sphere of `n` (over `a`
    /// perpendicular to `F^-T n` if incompressible). Sampled every 15 degrees in both angles of
    /// `n`; where the sampled minimum is below 5 % of the stiffness scale, refined by golden
    /// sections in each angle in turn around the best sample. Sampling overestimates the minimum
    /// by at most about 2 % of that scale (the curvature over half a 15 degree step), so every
    /// margin near zero, and its sign, is exact; a larger one is within about 2 %.
    pub fn ellipticity_margin(&self) -> f64 {
        // Q(n) = sum over (J, L) of A(e_J, e_L) n_J n_L, the six symmetric pairs summed once.
        let pairs: [Matrix3<f64>; 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)].map(|(jj, ll)| {
            let (a, b) = (self.contracted(e(jj), e(ll)), self.contracted(e(ll), e(jj)));
            let q = if jj == ll { a } else { a + b };
            (q + q.transpose()) * 0.5
        });
        let smallest_along = |n: [f64; 3]| {
            let q = pairs[0] * (n[0] * n[0])
                + pairs[1] * (n[1] * n[1])
                + pairs[2] * (n[2] * n[2])
                + pairs[3] * (n[0] * n[1])
                + pairs[4] * (n[0] * n[2])
                + pairs[5] * (n[1] * n[2]);
            if !self.incompressible {
                return smallest_eigenvalue(&q);
            }
            smallest_on_plane(&q, &Vector3::from_fn(|i, _| n[i] / self.stretches[i]).normalize())
        };
        let smallest = |polar: f64, azimuth: f64| smallest_along(surface_direction(polar, azimuth));
        let mut best = (0.0, 0.0, f64::INFINITY);
        for &(n, polar, azimuth) in margin_directions() {
            let value = smallest_along(n);
            if value < best.2 {
                best = (polar, azimuth, value);
            }
        }
        let scale = (0..3).map(|i| pairs[i].diagonal().abs().max()).fold(0.0, f64::max);
        if best.2 >= 0.05 * scale {
            return best.2;
        }
        let step = std::f64::consts::PI / MARGIN_STEPS as f64;
        let (mut polar, mut azimuth, mut value) = best;
        for _ in 0..3 {
            polar = golden_section(&|x| smallest(x, azimuth), polar, step, 30);
            azimuth = golden_section(&|x| smallest(polar, x), azimuth, step, 30);
            value = value.min(smallest(polar, azimuth));
        }
        value
    }
}
