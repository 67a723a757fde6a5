//! Incremental moduli of an orthotropic homogeneous state and the Stroh matrix of Appendix A,
//! for compressible and for exactly incompressible layers.

use crate::error::{Error, Result};
use crate::material::{add_pressure, Hyperelastic, Tensor2, Tensor4};
use nalgebra::Complex;

/// The components of `A = d2W/dF dF` (index `2i+J` for `F_iJ`) that survive at a diagonal `F`
/// of a material symmetric about the X axis (the fibre pair at `+-beta`):
/// `c11 = A_1111`, `c12 = A_1122`, `c22 = A_2222`, `c66 = A_1212`, `c69 = A_1221`,
/// `c99 = A_2121` (names after the Voigt-like positions 1, 2, 6, 9).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IncrementalModuli {
    pub c11: f64,
    pub c12: f64,
    pub c22: f64,
    pub c66: f64,
    pub c69: f64,
    pub c99: f64,
    /// `lambda_2 / lambda_1` of an incompressible state, whose increments obey
    /// `k a / lambda_1 + b' / lambda_2 = 0` (`tr(F^-1 Grad u) = 0`); `None` when compressible.
    pub incompressible_ratio: Option<f64>,
}

impl IncrementalModuli {
    /// Moduli of `material` at the deformation `f` (diagonal). The couplings between the
    /// normal-gradient group `(F11, F22)` and the shear-gradient group `(F12, F21)` must vanish.
    pub fn at<M: Hyperelastic>(material: &M, f: &Tensor2) -> Result<Self> {
        Self::of_tangent(&material.response(f)?.tangent, None)
    }

    /// Moduli of an incompressible layer (`rest` its energy without bulk term) at the diagonal
    /// `f` with `J = 1` and pressure `p`: those of the Lagrangian `W_rest + p ln J`,
    /// `A = A_rest + p d(F^-T)/dF`, on increments that keep `J = 1` to first order.
    pub fn incompressible<M: Hyperelastic>(rest: &M, f: &Tensor2, p: f64) -> Result<Self> {
        let mut response = rest.response(f)?;
        add_pressure(&mut response.stress, Some(&mut response.tangent), f, p);
        Self::of_tangent(&response.tangent, Some(f[3] / f[0]))
    }

    fn of_tangent(a: &Tensor4, incompressible_ratio: Option<f64>) -> Result<Self> {
        let scale = a.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
        let coupling = [a[0][1], a[0][2], a[3][1], a[3][2]]
            .iter()
            .fold(0.0f64, |s, x| s.max(x.abs()));
        if coupling > 1e-10 * scale {
            return Err(Error::NonFinite(format!(
                "stability analysis: tangent is not orthotropic about the X axis (coupling {coupling:e})"
            )));
        }
        Ok(IncrementalModuli {
            c11: a[0][0],
            c12: a[0][3],
            c22: a[3][3],
            c66: a[1][1],
            c69: a[1][2],
            c99: a[2][2],
            incompressible_ratio,
        })
    }

    /// Energy density of the increment per unit `Y`, averaged over a wavelength (times 2/pi k):
    /// the quadratic form of `g = (a, a', b, b')`, `E = g . C g`.
    pub fn energy_form(&self, k: f64) -> [[f64; 4]; 4] {
        let m = self;
        [
            [k * k * m.c11, 0.0, 0.0, k * m.c12],
            [0.0, m.c66, -k * m.c69, 0.0],
            [0.0, -k * m.c69, k * k * m.c99, 0.0],
            [k * m.c12, 0.0, 0.0, m.c22],
        ]
    }

    /// The two roots `p` of the characteristic quartic `det(N - p) = 0` with `Re p > 0` (the
    /// exponents `exp(k p Y)` of the solutions decaying as `Y -> -inf`). The quartic is
    /// biquadratic, `p^4 - (tr N^2 / 2) p^2 + det N = 0`, since the roots come in pairs `+-p`.
    pub fn decaying_roots(&self) -> [Complex<f64>; 2] {
        let n = self.stroh_matrix();
        let half_trace = 0.5 * (n * n).trace();
        let discriminant = Complex::new(half_trace * half_trace - 4.0 * n.determinant(), 0.0).sqrt();
        let root = |z: Complex<f64>| {
            let p = z.sqrt();
            if p.re < 0.0 {
                -p
            } else {
                p
            }
        };
        [
            root((half_trace + discriminant) * 0.5),
            root((half_trace - discriminant) * 0.5),
        ]
    }

    /// The Stroh matrix `N` of `y' = k N y` for `y = (a, b, s1/k, s2/k)`, where
    /// `s1 = c66 a' - k c69 b` and `s2 = k c12 a + c22 b'` are the amplitudes of the incremental
    /// nominal tractions `S_12` (sin kX) and `S_22` (cos kX) on planes `Y = const`.
    ///
    /// Incompressible (`r = lambda_2 / lambda_1`): the constraint gives `b' = -r k a`, and the
    /// incremental pressure `q cos kX` adds `q / lambda_1` to `S_11` and `q / lambda_2` to
    /// `S_22`. Eliminating `q` with `s2 = k c12 a + c22 b' + q / lambda_2` leaves
    /// `s1' = k (k (c11 - 2 r c12 + r^2 c22) a + r s2)`; the `b`- and `s2`-rows are unchanged.
    pub fn stroh_matrix(&self) -> nalgebra::Matrix4<f64> {
        let m = self;
        if let Some(r) = m.incompressible_ratio {
            return nalgebra::Matrix4::new(
                0.0,
                m.c69 / m.c66,
                1.0 / m.c66,
                0.0,
                -r,
                0.0,
                0.0,
                0.0,
                m.c11 - 2.0 * r * m.c12 + r * r * m.c22,
                0.0,
                0.0,
                r,
                0.0,
                m.c99 - m.c69 * m.c69 / m.c66,
                -m.c69 / m.c66,
                0.0,
            );
        }
        nalgebra::Matrix4::new(
            0.0,
            m.c69 / m.c66,
            1.0 / m.c66,
            0.0,
            -m.c12 / m.c22,
            0.0,
            0.0,
            1.0 / m.c22,
            m.c11 - m.c12 * m.c12 / m.c22,
            0.0,
            0.0,
            m.c12 / m.c22,
            0.0,
            m.c99 - m.c69 * m.c69 / m.c66,
            -m.c69 / m.c66,
            0.0,
        )
    }
}
