//! The two tissues of the model: the layer (cortex; neo-Hookean in the paper, any matrix law
//! here) and the fibre-reinforced substrate (white matter, eq. 3 mixture
//! `phi_m W_m + phi_f (f1 + f2)`), built from `Parameters`.

use super::growth::{Grown, Growth};
use super::laws::{Fibre, Matrix};
use super::{
    FibreFamily, FullResponse, Gent, HgoFamily, MooneyRivlin, NeoHookean, Ogden, Response, StrainEnergy, Tensor2,
};
use crate::error::Result;
use crate::parameters::{FibreLaw, Load, MatrixLaw, Parameters};
use num_dual::DualNum;

/// Substrate: a matrix plus two fibre families at `+-beta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreReinforced {
    pub matrix: Matrix,
    pub matrix_fraction: f64,
    pub fibre_fraction: f64,
    pub fibres: [Fibre; 2],
}

impl StrainEnergy for FibreReinforced {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        let fibres = self.fibres[0].density(f) + self.fibres[1].density(f);
        self.matrix.density(f) * self.matrix_fraction + fibres * self.fibre_fraction
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        let fibres = self.fibres[0]
            .plane_response(f)
            .plus(self.fibres[1].plane_response(f), 1.0);
        self.matrix
            .plane_response(f)
            .scaled(self.matrix_fraction)
            .plus(fibres, self.fibre_fraction)
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        // Summed in the order of `plane_response`, so that both give the same bits.
        let (wm, pm) = self.matrix.plane_stress(f);
        let ((w1, p1), (w2, p2)) = (self.fibres[0].plane_stress(f), self.fibres[1].plane_stress(f));
        let (m, c) = (self.matrix_fraction, self.fibre_fraction);
        (
            m * wm + c * (w1 + w2),
            std::array::from_fn(|a| m * pm[a] + c * (p1[a] + p2[a])),
        )
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        let fibres = self.fibres[0].response_3d(f).plus(self.fibres[1].response_3d(f), 1.0);
        self.matrix
            .response_3d(f)
            .scaled(self.matrix_fraction)
            .plus(fibres, self.fibre_fraction)
    }

    fn admissible(&self, f: &[f64; 9]) -> Result<()> {
        self.matrix.admissible(f)
    }

    fn bounded_domain(&self) -> bool {
        self.matrix.bounded_domain()
    }
}

/// Either tissue, so that code looping over elements of both layers needs one type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tissue {
    Layer(Grown<Matrix>),
    Substrate(Grown<FibreReinforced>),
}

impl StrainEnergy for Tissue {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 9]) -> D {
        match self {
            Tissue::Layer(m) => m.density(f),
            Tissue::Substrate(m) => m.density(f),
        }
    }

    fn plane_response(&self, f: &Tensor2) -> Response {
        match self {
            Tissue::Layer(m) => m.plane_response(f),
            Tissue::Substrate(m) => m.plane_response(f),
        }
    }

    fn plane_stress(&self, f: &Tensor2) -> (f64, Tensor2) {
        match self {
            Tissue::Layer(m) => m.plane_stress(f),
            Tissue::Substrate(m) => m.plane_stress(f),
        }
    }

    fn response_3d(&self, f: &[f64; 9]) -> FullResponse {
        match self {
            Tissue::Layer(m) => m.response_3d(f),
            Tissue::Substrate(m) => m.response_3d(f),
        }
    }

    fn admissible(&self, f: &[f64; 9]) -> Result<()> {
        match self {
            Tissue::Layer(m) => m.admissible(f),
            Tissue::Substrate(m) => m.admissible(f),
        }
    }

    fn bounded_domain(&self) -> bool {
        match self {
            Tissue::Layer(m) => m.bounded_domain(),
            Tissue::Substrate(m) => m.bounded_domain(),
        }
    }
}

/// The materials of both layers, from the parameters, with their growth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bilayer {
    pub layer: Grown<Matrix>,
    pub substrate: Grown<FibreReinforced>,
    /// Both layers exactly incompressible: `Je = det Fe = 1` is a constraint, and the energies
    /// above are the parts without bulk term (their bulk moduli are zero).
    pub incompressible: bool,
    /// What loads the bilayer; under a growth load the growths above are those at `g = 1`.
    pub load: Load,
    /// Whether a growth factor is of the in-plane area (else tangential).
    area_growth: bool,
}

impl Bilayer {
    pub fn new(p: &Parameters) -> Self {
        let bulk = |k: f64| if p.incompressible { 0.0 } else { k };
        let mut materials = Bilayer {
            layer: Grown::ungrown(matrix_law(&p.layer, p.mu_l, bulk(p.K_l))),
            substrate: Grown::ungrown(FibreReinforced {
                matrix: matrix_law(&p.substrate, p.mu_s, bulk(p.K_s)),
                matrix_fraction: p.phi_m,
                fibre_fraction: p.phi_f,
                fibres: [fibre_law(p, 1.0), fibre_law(p, -1.0)],
            }),
            incompressible: p.incompressible,
            load: p.load,
            area_growth: p.area_growth,
        };
        materials.layer.growth = materials.growth(p.growth_layer, 1.0);
        materials.substrate.growth = materials.growth(p.growth_substrate, 1.0);
        materials
    }

    /// The growth tensor of a growth factor `g` along `X` (and `g3` along `Z`), of the kind the
    /// parameters chose: the thickness grows with the length under area growth, else not.
    fn growth(&self, g: f64, g3: f64) -> Growth {
        Growth::in_surface(g, g3, self.area_growth)
    }

    /// The materials at the load's strain `d` and the stretch `lambda_1` of both layers along
    /// `X`: under compression the same materials at `lambda_1 = 1 - d`; under growth the growing
    /// layers at `g = 1 / (1 - d)`, with the ends held (`lambda_1 = 1`). Plane strain: nothing
    /// grows along `Z`.
    pub fn at_load(&self, d: f64) -> (Bilayer, f64) {
        let (loaded, [lambda1, _]) = self.at_biaxial_load(d, 0.0);
        (loaded, lambda1)
    }

    /// The materials at the load's strains `d` along `X` and `d_3` along `Z`, and the in-plane
    /// stretches `(lambda_1, lambda_3)` of both layers: under compression the same materials at
    /// `(1 - d, 1 - d_3)`; under growth the growing layers at `g = 1 / (1 - d)` along `X` and
    /// `g3 = 1 / (1 - d_3)` along `Z` (equal under equibiaxial growth, `Fg = diag(g, 1, g)`
    /// without thickening), with the sides held (`lambda_1 = lambda_3 = 1`).
    pub fn at_biaxial_load(&self, d: f64, d3: f64) -> (Bilayer, [f64; 2]) {
        let (g, g3) = (self.load.parameter(d), self.load.parameter(d3));
        let mut loaded = *self;
        match self.load {
            Load::Compression => return (loaded, [1.0 - d, 1.0 - d3]),
            Load::Growth => loaded.layer.growth = self.growth(g, g3),
            Load::UniformGrowth => {
                loaded.layer.growth = self.growth(g, g3);
                loaded.substrate.growth = self.growth(g, g3);
            }
        }
        (loaded, [1.0, 1.0])
    }

    /// Whether either layer grows, or growth is the load.
    pub fn grows(&self) -> bool {
        self.load.is_growth() || !(self.layer.growth.is_identity() && self.substrate.growth.is_identity())
    }

    pub fn layer_tissue(&self) -> Tissue {
        Tissue::Layer(self.layer)
    }

    pub fn substrate_tissue(&self) -> Tissue {
        Tissue::Substrate(self.substrate)
    }
}

/// A tissue's energy split as `W(F) = W_rest(F) + kappa/2 (ln J - ln Jg)^2` ([`Tissue::volumetric_split`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumetricSplit {
    /// The tissue with a zero bulk modulus (grown as the tissue is).
    pub rest: Tissue,
    /// `kappa`: the bulk modulus the tissue carries (`phi_m K_s` in the substrate), times `Jg`.
    pub bulk: f64,
    /// `ln Jg`, the volume the tissue is free of stress at.
    pub log_volume: f64,
}

impl Tissue {
    /// The tissue's growth `Fg`.
    pub fn growth(&self) -> Growth {
        match self {
            Tissue::Layer(m) => m.growth,
            Tissue::Substrate(m) => m.growth,
        }
    }

    /// The split `W(F) = W_rest(F) + kappa/2 (ln J - ln Jg)^2` of this tissue's energy:
    /// `W_rest` is the same tissue with a zero bulk modulus, `kappa` the bulk modulus it
    /// carries (`phi_m K_s` in the substrate) times `Jg`. Exact for the energies of
    /// `docs/model.md` ("Strain energies"), whose only `J`-term is `K/2 (ln J)^2`: grown, it is
    /// `Jg K/2 (ln Je)^2` with `ln Je = ln J - ln Jg`.
    pub fn volumetric_split(&self) -> VolumetricSplit {
        let (rest, bulk, growth) = match *self {
            Tissue::Layer(m) => (
                Tissue::Layer(Grown {
                    energy: m.energy.with_bulk_modulus(0.0),
                    growth: m.growth,
                }),
                m.energy.bulk_modulus(),
                m.growth,
            ),
            Tissue::Substrate(s) => {
                let rest = FibreReinforced {
                    matrix: s.energy.matrix.with_bulk_modulus(0.0),
                    ..s.energy
                };
                (
                    Tissue::Substrate(Grown {
                        energy: rest,
                        growth: s.growth,
                    }),
                    s.energy.matrix_fraction * s.energy.matrix.bulk_modulus(),
                    s.growth,
                )
            }
        };
        VolumetricSplit {
            rest,
            bulk: bulk * growth.jacobian(),
            log_volume: growth.jacobian().ln(),
        }
    }
}

/// A matrix law of shear modulus `mu` and bulk modulus `bulk`. The parameters are validated
/// ([`Parameters::validate`] requires every constant a law needs), so a missing one here is a bug.
fn matrix_law(law: &MatrixLaw, mu: f64, bulk: f64) -> Matrix {
    match law {
        MatrixLaw::NeoHookean => Matrix::NeoHookean(NeoHookean { mu, bulk }),
        MatrixLaw::MooneyRivlin { c1, c2 } => Matrix::MooneyRivlin(MooneyRivlin {
            c1: c1.expect(VALIDATED),
            c2: c2.expect(VALIDATED),
            bulk,
        }),
        MatrixLaw::Ogden { mu, alpha } => {
            let pairs: Vec<(f64, f64)> = mu.iter().copied().zip(alpha.iter().copied()).collect();
            Matrix::Ogden(Ogden::new(&pairs, bulk))
        }
        MatrixLaw::Gent { jm } => Matrix::Gent(Gent {
            mu,
            jm: jm.expect(VALIDATED),
            bulk,
        }),
    }
}

/// The fibre family along `(cos beta cos psi, sign sin beta, cos beta sin psi)`: inclined by
/// `beta` from the surface, at the azimuth `psi` from `X` in the surface plane.
fn fibre_law(p: &Parameters, sign: f64) -> Fibre {
    let direction = [
        p.beta.cos() * p.psi.cos(),
        sign * p.beta.sin(),
        p.beta.cos() * p.psi.sin(),
    ];
    match p.fibres {
        FibreLaw::Quadratic => Fibre::Quadratic(FibreFamily {
            stiffness: p.mu_f,
            prestretch: p.lambda_f,
            direction,
            tension_only: p.tension_only,
        }),
        FibreLaw::Hgo { k1, k2, kappa } => Fibre::Hgo(HgoFamily {
            k1: k1.expect(VALIDATED),
            k2: k2.expect(VALIDATED),
            kappa,
            direction,
            tension_only: p.tension_only,
        }),
    }
}

const VALIDATED: &str = "validated parameters hold every constant of their laws";
