//! The laws a tissue can be given, chosen at run time: a matrix law for the layer and for the
//! substrate's matrix, a fibre law for the substrate's two families. Each variant's energy,
//! stress and tangent are its own file's; these enums only dispatch.

use super::{
    FibreFamily, FullResponse, Gent, HgoFamily, MooneyRivlin, NeoHookean, Ogden, Response, StrainEnergy, Tensor2,
};
use crate::error::Result;
use num_dual::DualNum;

/// An isotropic matrix law (the layer, the substrate's matrix).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Matrix {
    NeoHookean(NeoHookean),
    MooneyRivlin(MooneyRivlin),
    Ogden(Ogden),
    Gent(Gent),
}

/// A fibre family's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fibre {
    Quadratic(FibreFamily),
    Hgo(HgoFamily),
}

macro_rules! dispatch {
    ($value:expr, $law:ident => $body:expr, $($variant:path),+) => {
        match $value {
            $($variant($law) => $body,)+
        }
    };
}

macro_rules! matrix {
    ($value:expr, $law:ident => $body:expr) => {
        dispatch!($value, $law => $body, Matrix::NeoHookean, Matrix::MooneyRivlin, Matrix::Ogden, Matrix::Gent)
    };
}

macro_rules! fibre {
    ($value:expr, $law:ident => $body:expr) => {
        dispatch!($value, $law => $body, Fibre::Quadratic, Fibre::Hgo)
    };
}

impl StrainEnergy for Matrix {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        matrix!(self, m => m.density(f))
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        matrix!(self, m => m.plane_response(f))
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        matrix!(self, m => m.plane_stress(f))
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        matrix!(self, m => m.response_3d(f))
    }

    fn admissible(&self, f: &[f64; 9]) -> Result<()> {
        matrix!(self, m => m.admissible(f))
    }

    fn bounded_domain(&self) -> bool {
        matrix!(self, m => m.bounded_domain())
    }
}

impl Matrix {
    /// The shear modulus in the reference state.
    pub fn shear_modulus(&self) -> f64 {
        match self {
            Matrix::NeoHookean(m) => m.mu,
            Matrix::MooneyRivlin(m) => 2.0 * (m.c1 + m.c2),
            Matrix::Ogden(m) => m.pairs().iter().map(|(mu, _)| mu).sum(),
            Matrix::Gent(m) => m.mu,
        }
    }

    /// The bulk modulus `K` of the volumetric term `K/2 (ln J)^2`, which every law has.
    pub fn bulk_modulus(&self) -> f64 {
        matrix!(self, m => m.bulk)
    }

    /// The same law with a bulk modulus `bulk`.
    pub fn with_bulk_modulus(self, bulk: f64) -> Matrix {
        match self {
            Matrix::NeoHookean(m) => Matrix::NeoHookean(NeoHookean { bulk, ..m }),
            Matrix::MooneyRivlin(m) => Matrix::MooneyRivlin(MooneyRivlin { bulk, ..m }),
            Matrix::Ogden(m) => Matrix::Ogden(Ogden { bulk, ..m }),
            Matrix::Gent(m) => Matrix::Gent(Gent { bulk, ..m }),
        }
    }
}

impl StrainEnergy for Fibre {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        fibre!(self, m => m.density(f))
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        fibre!(self, m => m.plane_response(f))
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        fibre!(self, m => m.plane_stress(f))
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        fibre!(self, m => m.response_3d(f))
    }
}

impl Fibre {
    /// `I4 = |F N|^2` along the family's direction `N`.
    pub fn stretch_invariant(&self, f: &Tensor2) -> f64 {
        let [c, s, out] = match self {
            Fibre::Quadratic(q) => q.direction,
            Fibre::Hgo(h) => h.direction,
        };
        let (a, b) = (f[0] * c + f[1] * s, f[2] * c + f[3] * s);
        a * a + b * b + out * out
    }

    /// Whether a tension-only family sits within `tolerance` of its kink at `f`, where the
    /// tangent jumps.
    pub fn near_kink(&self, f: &Tensor2, tolerance: f64) -> bool {
        match self {
            Fibre::Quadratic(q) => q.tension_only && (q.stretch_invariant(f) - q.prestretch.powi(2)).abs() < tolerance,
            Fibre::Hgo(h) => h.tension_only && h.plane_strain(f).abs() < tolerance,
        }
    }
}
