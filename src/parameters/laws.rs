//! The law of each tissue part and its constants, as the parameters hold them: a `[layer]`,
//! `[substrate]` and `[fibres]` table in a parameters file, dotted keys (`layer.alpha`) with
//! `--set`. The shear modulus (`mu_l`, `mu_s`) and the bulk modulus (`K_l`, `K_s`) of a matrix
//! law stay the flat keys, whatever the law: they fix the units and the contrast.

use super::table::{MODULUS_MAX, MODULUS_MIN};
use crate::error::{Error, Result};
use serde::Serialize;

/// A matrix law and the constants it has besides its shear and bulk moduli. A constant not
/// given yet is `None` (an empty list for Ogden's exponents); validation names it.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
#[serde(tag = "law", rename_all = "snake_case")]
pub enum MatrixLaw {
    #[default]
    NeoHookean,
    /// `W = c1 (Ibar1 - 3) + c2 (Ibar2 - 3)`: shear modulus `2 (c1 + c2)`.
    MooneyRivlin {
        #[serde(skip_serializing_if = "Option::is_none")]
        c1: Option<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        c2: Option<f64>,
    },
    /// `W = sum_p 2 mu_p / alpha_p^2 (sum_i Lbar_i^alpha_p - 3)`: shear modulus `sum_p mu_p`.
    Ogden { mu: Vec<f64>, alpha: Vec<f64> },
    /// `W = -mu jm / 2 ln(1 - (Ibar1 - 3) / jm)`.
    Gent {
        #[serde(skip_serializing_if = "Option::is_none")]
        jm: Option<f64>,
    },
}

/// The law of both fibre families.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
#[serde(tag = "law", rename_all = "snake_case")]
pub enum FibreLaw {
    /// The paper's `mu_f / 4 (I4 - lambda_f^2)^2` (constants `mu_f`, `lambda_f`).
    #[default]
    Quadratic,
    /// Holzapfel-Gasser-Ogden, `k1 / (2 k2) (exp(k2 E^2) - 1)`; `kappa` is 0 unless given.
    Hgo {
        #[serde(skip_serializing_if = "Option::is_none")]
        k1: Option<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        k2: Option<f64>,
        kappa: f64,
    },
}

/// The matrix laws by their names in files and on the command line.
pub const MATRIX_LAWS: [&str; 4] = ["neo_hookean", "mooney_rivlin", "ogden", "gent"];
/// The fibre laws by their names.
pub const FIBRE_LAWS: [&str; 2] = ["quadratic", "hgo"];
/// The Ogden law's largest number of terms.
pub const OGDEN_TERMS: usize = 3;

impl MatrixLaw {
    /// The law called `name`, of shear modulus `mu`, with its other constants still to give.
    pub fn named(key: &str, name: &str, mu: f64) -> Result<Self> {
        Ok(match name {
            "neo_hookean" => MatrixLaw::NeoHookean,
            "mooney_rivlin" => MatrixLaw::MooneyRivlin { c1: None, c2: None },
            "ogden" => MatrixLaw::Ogden {
                mu: vec![mu],
                alpha: Vec::new(),
            },
            "gent" => MatrixLaw::Gent { jm: None },
            other => return Err(Error::invalid(key, other, &MATRIX_LAWS.join(", "))),
        })
    }

    pub fn name(&self) -> &'static str {
        match self {
            MatrixLaw::NeoHookean => "neo_hookean",
            MatrixLaw::MooneyRivlin { .. } => "mooney_rivlin",
            MatrixLaw::Ogden { .. } => "ogden",
            MatrixLaw::Gent { .. } => "gent",
        }
    }

    /// The constants of this law under its table (besides `K`, which every law has).
    pub fn constants(&self) -> &'static [&'static str] {
        match self {
            MatrixLaw::NeoHookean => &["mu", "K"],
            MatrixLaw::MooneyRivlin { .. } => &["c1", "c2", "K"],
            MatrixLaw::Ogden { .. } => &["mu", "alpha", "K"],
            MatrixLaw::Gent { .. } => &["mu", "jm", "K"],
        }
    }

    /// The shear modulus the law's own constants fix, when they do (Mooney-Rivlin, Ogden).
    pub fn implied_shear_modulus(&self) -> Option<f64> {
        match self {
            MatrixLaw::MooneyRivlin {
                c1: Some(c1),
                c2: Some(c2),
            } => Some(2.0 * (c1 + c2)),
            MatrixLaw::Ogden { mu, .. } if !mu.is_empty() => Some(mu.iter().sum()),
            _ => None,
        }
    }

    /// Multiplies the law's moduli by `factor` (the shear modulus was changed as a whole).
    pub fn scale_moduli(&mut self, factor: f64) {
        match self {
            MatrixLaw::MooneyRivlin { c1, c2 } => {
                for c in [c1, c2].into_iter().flatten() {
                    *c *= factor;
                }
            }
            MatrixLaw::Ogden { mu, .. } => mu.iter_mut().for_each(|m| *m *= factor),
            MatrixLaw::NeoHookean | MatrixLaw::Gent { .. } => {}
        }
    }

    /// Sets the law's own constant `name` (not `K`, nor a neo-Hookean or Gent `mu`, which are
    /// the flat moduli); `table` is `layer` or `substrate`, for messages.
    pub fn set_constant(&mut self, table: &str, name: &str, value: &toml::Value) -> Result<()> {
        let key = format!("{table}.{name}");
        match (self, name) {
            (MatrixLaw::MooneyRivlin { c1, .. }, "c1") => *c1 = Some(number(&key, value)?),
            (MatrixLaw::MooneyRivlin { c2, .. }, "c2") => *c2 = Some(number(&key, value)?),
            (MatrixLaw::Ogden { mu, .. }, "mu") => *mu = numbers(&key, value)?,
            (MatrixLaw::Ogden { alpha, .. }, "alpha") => *alpha = numbers(&key, value)?,
            (MatrixLaw::Gent { jm }, "jm") => *jm = Some(number(&key, value)?),
            (law, _) => return Err(not_a_constant(&key, law.name(), law.constants())),
        }
        Ok(())
    }

    /// The law's own constants as `(name, value)`, in the order of [`MatrixLaw::constants`].
    pub fn entries(&self) -> Vec<(&'static str, toml::Value)> {
        let list = |v: &[f64]| toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect());
        let given = |name: &'static str, v: &Option<f64>| v.map(|x| (name, toml::Value::Float(x)));
        match self {
            MatrixLaw::NeoHookean => Vec::new(),
            MatrixLaw::MooneyRivlin { c1, c2 } => [given("c1", c1), given("c2", c2)].into_iter().flatten().collect(),
            MatrixLaw::Ogden { mu, alpha } => vec![("mu", list(mu)), ("alpha", list(alpha))],
            MatrixLaw::Gent { jm } => given("jm", jm).into_iter().collect(),
        }
    }

    /// The numeric constant `name` (an Ogden list only when it has one term).
    pub fn number(&self, table: &str, name: &str) -> Result<f64> {
        let key = format!("{table}.{name}");
        let absent = || missing(&key, self.name(), "a number");
        match (self, name) {
            (MatrixLaw::MooneyRivlin { c1, .. }, "c1") => c1.ok_or_else(absent),
            (MatrixLaw::MooneyRivlin { c2, .. }, "c2") => c2.ok_or_else(absent),
            (MatrixLaw::Gent { jm }, "jm") => jm.ok_or_else(absent),
            (MatrixLaw::Ogden { mu, alpha }, "mu" | "alpha") => {
                let list = if name == "mu" { mu } else { alpha };
                match list.as_slice() {
                    [x] => Ok(*x),
                    _ => Err(Error::invalid(
                        &key,
                        format!("{list:?}"),
                        "one term, to be read as one number",
                    )),
                }
            }
            (law, _) => Err(not_a_constant(&key, law.name(), law.constants())),
        }
    }

    /// Checks the law's constants against the shear modulus `mu` of the table `table`
    /// (`mu_name` its flat key).
    pub fn validate(&self, table: &str, mu_name: &str, mu: f64) -> Result<()> {
        let require = |name: &str, v: Option<f64>, allowed: &str, ok: &dyn Fn(f64) -> bool| -> Result<f64> {
            let key = format!("{table}.{name}");
            let v = v.ok_or_else(|| missing(&key, self.name(), allowed))?;
            if v.is_finite() && ok(v) {
                Ok(v)
            } else {
                Err(Error::invalid_number(&key, v, allowed))
            }
        };
        match self {
            MatrixLaw::NeoHookean => {}
            MatrixLaw::MooneyRivlin { c1, c2 } => {
                let modulus = |x: f64| (0.0..=MODULUS_MAX).contains(&x);
                let c1 = require("c1", *c1, "[0, 1e12] (units of mu_s)", &modulus)?;
                let c2 = require(
                    "c2",
                    *c2,
                    "[0, 1e12] (units of mu_s; c2 < 0 loses ellipticity)",
                    &modulus,
                )?;
                if c1 + c2 <= 0.0 {
                    return Err(Error::invalid(&format!("{table}.c1"), c1, "c1 + c2 > 0"));
                }
            }
            MatrixLaw::Ogden { mu, alpha } => {
                let key = |name: &str| format!("{table}.{name}");
                if alpha.is_empty() {
                    return Err(missing(&key("alpha"), "ogden", "a number or a list of 1 to 3 numbers"));
                }
                if alpha.len() > OGDEN_TERMS || alpha.len() != mu.len() {
                    return Err(Error::invalid(
                        &key("alpha"),
                        format!("{alpha:?}"),
                        &format!("a list of 1 to 3 numbers, as long as {} = {mu:?}", key("mu")),
                    ));
                }
                for &a in alpha {
                    if !(a.is_finite() && a != 0.0 && a.abs() <= 100.0) {
                        return Err(Error::invalid_number(&key("alpha"), a, "[-100, 100] without 0"));
                    }
                }
                for &m in mu {
                    if !(m.is_finite() && (MODULUS_MIN..=MODULUS_MAX).contains(&m)) {
                        return Err(Error::invalid_number(
                            &key("mu"),
                            m,
                            "each term in [1e-12, 1e12] (units of mu_s)",
                        ));
                    }
                }
            }
            MatrixLaw::Gent { jm } => {
                require("jm", *jm, "(0, 1e12]", &|x| x > 0.0 && x <= MODULUS_MAX)?;
            }
        }
        if let Some(implied) = self.implied_shear_modulus() {
            if (implied - mu).abs() > 1e-12 * mu.abs() {
                return Err(Error::invalid(
                    mu_name,
                    mu,
                    &format!("the shear modulus its {table} law's constants give, {implied}"),
                ));
            }
        }
        Ok(())
    }
}

impl FibreLaw {
    pub fn named(name: &str) -> Result<Self> {
        match name {
            "quadratic" => Ok(FibreLaw::Quadratic),
            "hgo" => Ok(FibreLaw::Hgo {
                k1: None,
                k2: None,
                kappa: 0.0,
            }),
            other => Err(Error::invalid("fibres.law", other, &FIBRE_LAWS.join(", "))),
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            FibreLaw::Quadratic => "quadratic",
            FibreLaw::Hgo { .. } => "hgo",
        }
    }

    /// The constants of this law under `[fibres]` (besides `tension_only`, which both have).
    pub fn constants(&self) -> &'static [&'static str] {
        match self {
            FibreLaw::Quadratic => &["mu_f", "lambda_f"],
            FibreLaw::Hgo { .. } => &["k1", "k2", "kappa"],
        }
    }

    /// Sets an HGO constant (`mu_f` and `lambda_f` are the flat keys).
    pub fn set_constant(&mut self, name: &str, value: &toml::Value) -> Result<()> {
        let key = format!("fibres.{name}");
        match (self, name) {
            (FibreLaw::Hgo { k1, .. }, "k1") => *k1 = Some(number(&key, value)?),
            (FibreLaw::Hgo { k2, .. }, "k2") => *k2 = Some(number(&key, value)?),
            (FibreLaw::Hgo { kappa, .. }, "kappa") => *kappa = number(&key, value)?,
            (law, _) => return Err(not_a_constant(&key, law.name(), law.constants())),
        }
        Ok(())
    }

    pub fn number(&self, name: &str) -> Result<f64> {
        let key = format!("fibres.{name}");
        let absent = || missing(&key, "hgo", "a number");
        match (self, name) {
            (FibreLaw::Hgo { k1, .. }, "k1") => k1.ok_or_else(absent),
            (FibreLaw::Hgo { k2, .. }, "k2") => k2.ok_or_else(absent),
            (FibreLaw::Hgo { kappa, .. }, "kappa") => Ok(*kappa),
            (law, _) => Err(not_a_constant(&key, law.name(), law.constants())),
        }
    }

    pub fn entries(&self) -> Vec<(&'static str, toml::Value)> {
        match self {
            FibreLaw::Quadratic => Vec::new(),
            FibreLaw::Hgo { k1, k2, kappa } => [("k1", *k1), ("k2", *k2), ("kappa", Some(*kappa))]
                .into_iter()
                .filter_map(|(name, v)| v.map(|x| (name, toml::Value::Float(x))))
                .collect(),
        }
    }

    pub fn validate(&self) -> Result<()> {
        if let FibreLaw::Hgo { k1, k2, kappa } = self {
            let check = |name: &str, v: Option<f64>, lo: f64, hi: f64, allowed: &str| -> Result<()> {
                let key = format!("fibres.{name}");
                match v {
                    None => Err(missing(&key, "hgo", allowed)),
                    Some(x) if x.is_finite() && (lo..=hi).contains(&x) => Ok(()),
                    Some(x) => Err(Error::invalid_number(&key, x, allowed)),
                }
            };
            check("k1", *k1, 0.0, MODULUS_MAX, "[0, 1e12] (units of mu_s)")?;
            check("k2", *k2, 0.0, 1e3, "[0, 1000]")?;
            check("kappa", Some(*kappa), 0.0, 1.0 / 3.0, "[0, 1/3]")?;
        }
        Ok(())
    }
}

pub(super) fn not_a_constant(key: &str, law: &str, constants: &[&str]) -> Error {
    Error::NotAConstant {
        name: key.to_string(),
        law: law.to_string(),
        constants: constants.join(", "),
    }
}

fn missing(key: &str, law: &str, allowed: &str) -> Error {
    Error::MissingConstant {
        name: key.to_string(),
        law: law.to_string(),
        allowed: allowed.to_string(),
    }
}

/// A TOML number as `f64`.
pub(super) fn number(key: &str, value: &toml::Value) -> Result<f64> {
    match value {
        toml::Value::Float(x) => Ok(*x),
        toml::Value::Integer(i) => Ok(*i as f64),
        other => Err(Error::invalid(key, other, "a number")),
    }
}

/// A TOML number or list of numbers as a list.
fn numbers(key: &str, value: &toml::Value) -> Result<Vec<f64>> {
    match value {
        toml::Value::Array(items) => items.iter().map(|v| number(key, v)).collect(),
        other => Ok(vec![number(key, other)?]),
    }
}
