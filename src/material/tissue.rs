//! The two tissues of the model: the layer (cortex, neo-Hookean) and the fibre-reinforced
//! substrate (white matter, eq. 3 mixture `phi_m W_m + phi_f (f1 + f2)`), built from `Parameters`.

use super::{FibreFamily, NeoHookean, Response, StrainEnergy, Tensor2};
use crate::parameters::Parameters;
use num_dual::DualNum;

/// Substrate: neo-Hookean matrix plus two fibre families at `+-beta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreReinforced {
    pub matrix: NeoHookean,
    pub matrix_fraction: f64,
    pub fibre_fraction: f64,
    pub fibres: [FibreFamily; 2],
}

impl StrainEnergy for FibreReinforced {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 4], f33: D) -> D {
        let fibres = self.fibres[0].density(f, f33) + self.fibres[1].density(f, f33);
        self.matrix.density(f, f33) * self.matrix_fraction + fibres * self.fibre_fraction
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
}

/// Either tissue, so that code looping over elements of both layers needs one type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tissue {
    Layer(NeoHookean),
    Substrate(FibreReinforced),
}

impl StrainEnergy for Tissue {
    fn density<D: DualNum<Primitive = f64> + Copy>(&self, f: &[D; 4], f33: D) -> D {
        match self {
            Tissue::Layer(m) => m.density(f, f33),
            Tissue::Substrate(m) => m.density(f, f33),
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
}

/// The materials of both layers, from the parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bilayer {
    pub layer: NeoHookean,
    pub substrate: FibreReinforced,
    /// Both layers exactly incompressible: `J = 1` is a constraint, and the energies above are
    /// the parts without bulk term (their bulk moduli are zero).
    pub incompressible: bool,
}

impl Bilayer {
    pub fn new(p: &Parameters) -> Self {
        let family = |sign: f64| FibreFamily {
            stiffness: p.mu_f,
            prestretch: p.lambda_f,
            direction: [p.beta.cos(), sign * p.beta.sin()],
            tension_only: p.tension_only,
        };
        let bulk = |k: f64| if p.incompressible { 0.0 } else { k };
        Bilayer {
            layer: NeoHookean {
                mu: p.mu_l,
                bulk: bulk(p.K_l),
            },
            substrate: FibreReinforced {
                matrix: NeoHookean {
                    mu: p.mu_s,
                    bulk: bulk(p.K_s),
                },
                matrix_fraction: p.phi_m,
                fibre_fraction: p.phi_f,
                fibres: [family(1.0), family(-1.0)],
            },
            incompressible: p.incompressible,
        }
    }

    pub fn layer_tissue(&self) -> Tissue {
        Tissue::Layer(self.layer)
    }

    pub fn substrate_tissue(&self) -> Tissue {
        Tissue::Substrate(self.substrate)
    }
}

impl Tissue {
    /// The split `W(F) = W_rest(F) + kappa/2 (ln J)^2` of this tissue's energy: `W_rest` is the
    /// same tissue with a zero bulk modulus, `kappa` the bulk modulus it carries (`phi_m K_s` in
    /// the substrate). Exact for the energies of `docs/model.md` ("Strain energies"), whose only
    /// `J`-term is `K/2 (ln J)^2`.
    pub fn volumetric_split(&self) -> (Tissue, f64) {
        match *self {
            Tissue::Layer(m) => (Tissue::Layer(NeoHookean { bulk: 0.0, ..m }), m.bulk),
            Tissue::Substrate(s) => {
                let rest = FibreReinforced {
                    matrix: NeoHookean { bulk: 0.0, ..s.matrix },
                    ..s
                };
                (Tissue::Substrate(rest), s.matrix_fraction * s.matrix.bulk)
            }
        }
    }
}
