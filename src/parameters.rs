//! Model parameters: one typed, validated struct with the paper's Table 1 as `Default`,
//! loadable from TOML and overridable key by key (`--set KEY=VALUE`).
//!
//! Units are the paper's: lengths by the layer thickness H, moduli by the substrate shear
//! modulus (so `mu_s = 1` by default).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Material parameters of the bilayer (the paper's Table 1 and eqs. 1-3; `docs/model.md`, "Parameters").
#[allow(non_snake_case)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Parameters {
    /// Shear modulus of the layer (cortex).
    pub mu_l: f64,
    /// Bulk modulus of the layer.
    pub K_l: f64,
    /// Shear modulus of the substrate matrix (the unit of stress).
    pub mu_s: f64,
    /// Bulk modulus of the substrate matrix.
    pub K_s: f64,
    /// Volume fraction of the substrate matrix.
    pub phi_m: f64,
    /// Volume fraction of *each* fibre family: eq. 3 (and eq. 4a, which it reproduces) weights
    /// both `f(I4)` terms by `phi_f`. The paper reads both ways: Table 1 lists `phi_f = 0.1`
    /// beside `phi_m = 0.9` as if it were the total, while the text says each family has 0.05
    /// (`reproduce` sets the claims of Figs. 4b-6 under both readings side by side).
    pub phi_f: f64,
    /// Fibre stiffness in `f(I4) = mu_f/4 (I4 - lambda_f^2)^2`.
    pub mu_f: f64,
    /// Fibre pre-stretch parameter (`lambda_f < 1`: fibres in tension in the reference state).
    pub lambda_f: f64,
    /// Fibre angle in radians: families along `(cos beta, +-sin beta)`.
    pub beta: f64,
    /// When true, fibres carry no load while `I4 < lambda_f^2`.
    pub tension_only: bool,
    /// When true, both layers are exactly incompressible (`J = 1`, enforced by a pressure
    /// multiplier) and `K_l`, `K_s` are not used.
    #[serde(default)]
    pub incompressible: bool,
}

impl Default for Parameters {
    /// The paper's Table 1 (benchmark values) with horizontal fibres.
    fn default() -> Self {
        Parameters {
            mu_l: 10.0,
            K_l: 30.0,
            mu_s: 1.0,
            K_s: 3.0,
            phi_m: 0.9,
            phi_f: 0.1,
            mu_f: 10.0,
            lambda_f: 1.0,
            beta: 0.0,
            tension_only: false,
            incompressible: false,
        }
    }
}

/// The parameter names, in the order they are printed.
pub const PARAMETER_NAMES: [&str; 11] = [
    "mu_l",
    "K_l",
    "mu_s",
    "K_s",
    "phi_m",
    "phi_f",
    "mu_f",
    "lambda_f",
    "beta",
    "tension_only",
    "incompressible",
];

/// The parameters that are `true` or `false` (the others are numbers).
pub fn is_boolean(key: &str) -> bool {
    matches!(key, "tension_only" | "incompressible")
}

impl Parameters {
    /// Reads a TOML file; keys not given keep their Table 1 defaults.
    pub fn from_toml_file(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::ParameterSyntax(format!("--params {}: {e}", path.display())))?;
        Self::from_toml_str(&text).map_err(|e| match e {
            Error::ParameterSyntax(m) => Error::ParameterSyntax(format!("{}: {m}", path.display())),
            other => other,
        })
    }

    /// Parses TOML text; keys not given keep their Table 1 defaults.
    pub fn from_toml_str(text: &str) -> Result<Self> {
        let table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| Error::ParameterSyntax(e.message().to_string()))?;
        let mut params = Parameters::default();
        for (key, value) in table {
            params.set_value(&key, value)?;
        }
        params.validate()?;
        Ok(params)
    }

    /// Applies one `KEY=VALUE` override (the command line's `--set`); its range, as every
    /// parameter's, is checked by [`Parameters::validate`] (so `K_s=inf` gets the same message
    /// as in a file).
    pub fn set(&mut self, assignment: &str) -> Result<()> {
        let (key, value) = assignment
            .split_once('=')
            .ok_or_else(|| Error::ParameterSyntax(format!("`--set {assignment}` must have the form KEY=VALUE")))?;
        let key = key.trim();
        if !PARAMETER_NAMES.contains(&key) {
            return Err(unknown_parameter(key));
        }
        let text = value.trim();
        let value = if is_boolean(key) {
            toml::Value::Boolean(parse_bool(key, text)?)
        } else {
            toml::Value::Float(text.parse().map_err(|_| Error::invalid(key, text, "a number"))?)
        };
        self.set_value(key, value)
    }

    fn set_value(&mut self, key: &str, value: toml::Value) -> Result<()> {
        if is_boolean(key) {
            let flag = match value {
                toml::Value::Boolean(b) => b,
                other => return Err(Error::invalid(key, other, "true or false")),
            };
            *self.flag_mut(key)? = flag;
            return Ok(());
        }
        let number = match value {
            toml::Value::Float(x) => x,
            toml::Value::Integer(i) => i as f64,
            other => return Err(Error::invalid(key, other, "a number")),
        };
        *self.number_mut(key)? = number;
        Ok(())
    }

    /// The `true`/`false` parameter called `key` ([`is_boolean`]).
    pub fn flag(&self, key: &str) -> Result<bool> {
        self.clone().flag_mut(key).map(|flag| *flag)
    }

    /// Mutable access to the `true`/`false` parameter called `key` ([`is_boolean`]).
    pub fn flag_mut(&mut self, key: &str) -> Result<&mut bool> {
        match key {
            "tension_only" => Ok(&mut self.tension_only),
            "incompressible" => Ok(&mut self.incompressible),
            _ => Err(unknown_parameter(key)),
        }
    }

    /// The numeric parameter called `key` (the names of `PARAMETER_NAMES`).
    pub fn number(&self, key: &str) -> Result<f64> {
        let mut copy = self.clone();
        copy.number_mut(key).map(|x| *x)
    }

    /// Mutable access to the numeric parameter called `key`, for sweeps.
    pub fn number_mut(&mut self, key: &str) -> Result<&mut f64> {
        Ok(match key {
            "mu_l" => &mut self.mu_l,
            "K_l" => &mut self.K_l,
            "mu_s" => &mut self.mu_s,
            "K_s" => &mut self.K_s,
            "phi_m" => &mut self.phi_m,
            "phi_f" => &mut self.phi_f,
            "mu_f" => &mut self.mu_f,
            "lambda_f" => &mut self.lambda_f,
            "beta" => &mut self.beta,
            _ => return Err(unknown_parameter(key)),
        })
    }

    /// Checks every range; the message names the parameter and its allowed range.
    pub fn validate(&self) -> Result<()> {
        // Moduli within 12 orders of magnitude of the unit mu_s = 1 (K/mu = 1e6 is nearly
        // incompressible tissue; beyond 1e12 the energy's derivatives lose all precision).
        let moduli = [
            ("mu_l", self.mu_l),
            ("K_l", self.K_l),
            ("mu_s", self.mu_s),
            ("K_s", self.K_s),
        ];
        for (name, value) in moduli {
            if !(value.is_finite() && (MODULUS_MIN..=MODULUS_MAX).contains(&value)) {
                return Err(Error::invalid_number(name, value, modulus_range(name)));
            }
        }
        if !(self.mu_f.is_finite() && (0.0..=MODULUS_MAX).contains(&self.mu_f)) {
            return Err(Error::invalid_number("mu_f", self.mu_f, "[0, 1e12] (in units of mu_s)"));
        }
        if !(self.lambda_f.is_finite() && self.lambda_f > 0.0 && self.lambda_f <= 10.0) {
            return Err(Error::invalid_number("lambda_f", self.lambda_f, "(0, 10]"));
        }
        for (name, value) in [("phi_m", self.phi_m), ("phi_f", self.phi_f)] {
            if !(value.is_finite() && (0.0..=1.0).contains(&value)) {
                return Err(Error::invalid(name, value, "[0, 1]"));
            }
        }
        if !self.beta.is_finite() {
            return Err(Error::invalid("beta", self.beta, "a finite angle in radians"));
        }
        Ok(())
    }

    /// The resolved set as TOML that `--params` reads back.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).expect("a struct of numbers always serialises");
        format!("{PHI_F_NOTE}\n{body}")
    }
}

/// Smallest and largest moduli accepted (units of `mu_s`).
const MODULUS_MIN: f64 = 1e-12;
const MODULUS_MAX: f64 = 1e12;

/// What `phi_f` means, written at the top of every parameter file (a TOML comment).
pub const PHI_F_NOTE: &str = "# phi_f is the volume fraction of EACH of the two fibre families (eq. 3 weights both \
    f(I4) terms by it).\n# The paper reads both ways: Table 1 gives phi_f = 0.1 next to phi_m = 0.9, the text \
    'phi_f = 0.05 for each family'.";

fn unknown_parameter(key: &str) -> Error {
    Error::UnknownParameter {
        name: key.to_string(),
        known: PARAMETER_NAMES.join(", "),
    }
}

/// Validates an end-shortening `d = 1 - lambda_1`.
pub fn validate_compression(name: &str, d: f64) -> Result<()> {
    if d.is_finite() && (0.0..1.0).contains(&d) {
        Ok(())
    } else {
        Err(Error::invalid(name, d, "[0, 1)"))
    }
}

/// The allowed range of the modulus `name`; a bulk modulus beyond it (e.g. `K_s = inf`) is
/// pointed to exact incompressibility.
fn modulus_range(name: &str) -> &'static str {
    if name.starts_with('K') {
        "a finite number in [1e-12, 1e12] (moduli in units of mu_s; for exactly incompressible layers set incompressible = true)"
    } else {
        "a finite number in [1e-12, 1e12] (moduli in units of mu_s)"
    }
}

/// Parses a finite number given for `name`.
pub fn parse_number(name: &str, text: &str) -> Result<f64> {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(Error::invalid(name, text, "a finite number")),
    }
}

fn parse_bool(name: &str, text: &str) -> Result<bool> {
    text.parse::<bool>()
        .map_err(|_| Error::invalid(name, text, "true or false"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_table_1_and_round_trip_through_toml() {
        let p = Parameters::default();
        p.validate().unwrap();
        assert_eq!(Parameters::from_toml_str(&p.to_toml()).unwrap(), p);
    }

    #[test]
    fn set_overrides_and_rejects() {
        let mut p = Parameters::default();
        p.set("beta=0.5").unwrap();
        p.set("tension_only=true").unwrap();
        assert_eq!(p.beta, 0.5);
        assert!(p.tension_only);
        let unknown = p.set("gamma=1").unwrap_err().to_string();
        assert!(unknown.contains("gamma") && unknown.contains("mu_f"), "{unknown}");
        assert!(p.set("mu_l=abc").is_err());
        assert!(p.set("mu_l").is_err());
    }

    #[test]
    fn integers_in_toml_are_numbers() {
        let p = Parameters::from_toml_str("mu_f = 20\nbeta = 0.25").unwrap();
        assert_eq!(p.mu_f, 20.0);
        assert_eq!(p.beta, 0.25);
    }

    #[test]
    fn validation_names_parameter_and_range() {
        let p = Parameters {
            phi_f: 1.5,
            ..Parameters::default()
        };
        let msg = p.validate().unwrap_err().to_string();
        assert!(msg.contains("phi_f") && msg.contains("[0, 1]"), "{msg}");
        let p = Parameters {
            mu_l: -1.0,
            ..Parameters::default()
        };
        assert!(p.validate().unwrap_err().to_string().contains("mu_l"));
        // An infinite bulk modulus, in a file or after --set, is pointed to incompressible = true.
        let file = Parameters::from_toml_str("K_s = inf");
        let set = |assignment: &str| {
            let mut p = Parameters::default();
            p.set(assignment).and_then(|_| p.validate()).unwrap_err().to_string()
        };
        for msg in [file.unwrap_err().to_string(), set("K_l=inf")] {
            assert!(msg.contains("incompressible = true") && msg.contains("1e12"), "{msg}");
        }
        assert!(!set("mu_l=inf").contains("incompressible"));
        assert!(validate_compression("d", 1.0).is_err());
        assert!(validate_compression("d", f64::NAN).is_err());
    }
}
