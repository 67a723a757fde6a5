//! Model parameters: one typed, validated struct with the paper's Table 1 as `Default`,
//! loadable from TOML and overridable key by key (`--set KEY=VALUE`).
//!
//! Units are the paper's: lengths by the layer thickness H, moduli by the substrate shear
//! modulus (so `mu_s = 1` by default).

mod laws;
mod load;
mod table;

pub use laws::{FibreLaw, MatrixLaw, FIBRE_LAWS, MATRIX_LAWS, OGDEN_TERMS};
pub use load::{Load, LOADS};
pub use table::{help as set_help, Kind, Range, Spec, TABLE};

use crate::error::{Error, Result};
use laws::number;
use serde::{Deserialize, Deserializer, Serialize};
use std::path::Path;

/// Material parameters of the bilayer (the paper's Table 1 and eqs. 1-3; `docs/model.md`, "Parameters").
#[allow(non_snake_case)]
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Parameters {
    /// Shear modulus of the layer (cortex), whatever its law.
    pub mu_l: f64,
    /// Bulk modulus of the layer.
    pub K_l: f64,
    /// Shear modulus of the substrate matrix (the unit of stress), whatever its law.
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
    /// Fibre inclination from the surface in radians: families along `(cos beta, +-sin beta)` in
    /// the X-Y plane of the paper.
    pub beta: f64,
    /// Fibre azimuth in the surface plane in radians (from X towards Z): families along
    /// `(cos beta cos psi, +-sin beta, cos beta sin psi)`; 0 is the paper's case.
    pub psi: f64,
    /// When true, fibres carry no load while `I4 < lambda_f^2`.
    pub tension_only: bool,
    /// When true, both layers are exactly incompressible (`J = 1`, enforced by a pressure
    /// multiplier) and `K_l`, `K_s` are not used.
    pub incompressible: bool,
    /// The layer's law (`[layer]`; neo-Hookean by default).
    pub layer: MatrixLaw,
    /// The substrate matrix's law (`[substrate]`).
    pub substrate: MatrixLaw,
    /// The fibres' law (`[fibres]`; the paper's quadratic one by default).
    pub fibres: FibreLaw,
    /// Growth of the layer, fixed (a prestress before a compression) unless it is the load.
    pub growth_layer: f64,
    /// Growth of the substrate, fixed.
    pub growth_substrate: f64,
    /// When true the thickness grows as the length does, `Fg = diag(g, g, g3)` (the layer
    /// thickens); otherwise `Fg = diag(g, 1, g3)`. `g3 = 1` in plane strain; on a patch under
    /// the biaxiality `R`, `g3 = 1/(1 - R d)` under a growth load.
    pub area_growth: bool,
    /// What loads the bilayer: the end-shortening `d` or the growth `g` (`load`).
    pub load: Load,
}

impl Default for Parameters {
    /// The paper's Table 1 (benchmark values) with horizontal fibres: the defaults of [`TABLE`].
    fn default() -> Self {
        let mut p = Parameters {
            mu_l: 0.0,
            K_l: 0.0,
            mu_s: 0.0,
            K_s: 0.0,
            phi_m: 0.0,
            phi_f: 0.0,
            mu_f: 0.0,
            lambda_f: 0.0,
            beta: 0.0,
            psi: 0.0,
            tension_only: false,
            incompressible: false,
            layer: MatrixLaw::NeoHookean,
            substrate: MatrixLaw::NeoHookean,
            fibres: FibreLaw::Quadratic,
            growth_layer: 0.0,
            growth_substrate: 0.0,
            area_growth: false,
            load: Load::Compression,
        };
        for s in &TABLE {
            match s.kind {
                Kind::Number { default, field, .. } => *field(&mut p) = default,
                Kind::Flag { default, field } => *field(&mut p) = default,
            }
        }
        p
    }
}

/// The flat parameter names, in the order they are printed.
pub fn parameter_names() -> impl Iterator<Item = &'static str> {
    TABLE.iter().map(|s| s.name)
}

/// The tables of the laws (`[layer]` in a file, `layer.KEY` with `--set`).
pub const LAW_TABLES: [&str; 3] = ["layer", "substrate", "fibres"];

/// The parameters that are `true` or `false` (the others are numbers, law names or lists).
pub fn is_boolean(key: &str) -> bool {
    key == "fibres.tension_only" || matches!(table::spec(key).map(|s| &s.kind), Some(Kind::Flag { .. }))
}

impl Parameters {
    /// The direction of the fibres' projection on the surface, `(cos psi, sin psi)` in the
    /// `X-Z` plane; `None` for fibres normal to it (`beta = pi/2`), which have no azimuth.
    pub fn fibre_projection(&self) -> Option<[f64; 2]> {
        (self.beta.cos() > 1e-6).then(|| [self.psi.cos(), self.psi.sin()])
    }

    /// Reads a TOML file; keys not given keep their Table 1 defaults.
    pub fn from_toml_file(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::ParameterSyntax(format!("--params {}: {e}", path.display())))?;
        Self::from_toml_str(&text).map_err(|e| match e {
            Error::ParameterSyntax(m) => Error::ParameterSyntax(format!("{}: {m}", path.display())),
            other => other,
        })
    }

    /// Parses TOML text; keys not given keep their Table 1 defaults. The flat keys are applied
    /// first, then the law tables, each with its `law` first, so that the order in the file
    /// does not matter.
    pub fn from_toml_str(text: &str) -> Result<Self> {
        let table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| Error::ParameterSyntax(e.message().to_string()))?;
        Self::from_table(&table)
    }

    /// The parameters of a table as a file holds them (flat keys and law tables), validated.
    fn from_table(table: &toml::Table) -> Result<Self> {
        let mut params = Parameters::default();
        let (tables, flat): (Vec<_>, Vec<_>) = table.iter().partition(|(_, v)| v.is_table());
        for (key, value) in flat {
            params.set_value(key, value)?;
        }
        for (key, value) in tables {
            params.set_value(key, value)?;
        }
        params.validate()?;
        Ok(params)
    }

    /// Applies one `KEY=VALUE` override (the command line's `--set`); its range, as every
    /// parameter's, is checked by [`Parameters::validate`] (so `K_s=inf` gets the same message
    /// as in a file). `VALUE` is read as a TOML value (a number, `true`, a list `[-25, 2]`),
    /// or else as a bare name (`layer.law=ogden`).
    pub fn set(&mut self, assignment: &str) -> Result<()> {
        let (key, value) = assignment
            .split_once('=')
            .ok_or_else(|| Error::ParameterSyntax(format!("`--set {assignment}` must have the form KEY=VALUE")))?;
        let (key, text) = (key.trim(), value.trim());
        let value = format!("v = {text}")
            .parse::<toml::Table>()
            .ok()
            .and_then(|mut t| t.remove("v"))
            .unwrap_or_else(|| toml::Value::String(text.to_string()));
        self.set_value(key, &value)
    }

    /// Sets the numeric parameter `key` (a flat key or a law constant such as `layer.alpha`).
    pub fn set_number(&mut self, key: &str, value: f64) -> Result<()> {
        self.number(key)?;
        self.set_value(key, &toml::Value::Float(value))
    }

    /// Sets the numeric `key` to `value`; a shear modulus (`mu_l`, `mu_s`) takes its bulk
    /// modulus (`K_l`, `K_s`) along by the same factor, keeping Poisson's ratio, unless that bulk
    /// modulus is one of `set_apart` (set on its own, as the other axis of a map).
    pub fn set_number_keeping_poisson(&mut self, key: &str, value: f64, set_apart: &[&str]) -> Result<()> {
        let bulk = match key {
            "mu_l" => Some(("K_l", self.K_l / self.mu_l)),
            "mu_s" => Some(("K_s", self.K_s / self.mu_s)),
            _ => None,
        };
        if let Some((bulk, ratio)) = bulk.filter(|(bulk, _)| !set_apart.contains(bulk)) {
            self.set_number(bulk, ratio * value)?;
        }
        self.set_number(key, value)
    }

    /// What is legal but probably not meant, one line each: a layer with a negative Poisson
    /// ratio (`K < 2 mu / 3`), volume fractions adding up to more than 1.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        if !self.incompressible {
            for (layer, mu, bulk, names) in [
                ("layer", self.mu_l, self.K_l, ("K_l", "mu_l")),
                ("substrate", self.mu_s, self.K_s, ("K_s", "mu_s")),
            ] {
                if bulk < 2.0 * mu / 3.0 {
                    let nu = (3.0 * bulk - 2.0 * mu) / (2.0 * (3.0 * bulk + mu));
                    warnings.push(format!(
                        "the {layer} has a negative Poisson ratio ({} / {} = {:.3} < 2/3: nu = {nu:.3})",
                        names.0,
                        names.1,
                        bulk / mu
                    ));
                }
            }
        }
        if self.phi_m + self.phi_f > 1.0 + 1e-12 {
            warnings.push(format!(
                "phi_m + phi_f = {} exceeds 1 (phi_f is each fibre family's fraction)",
                self.phi_m + self.phi_f
            ));
        }
        warnings
    }

    /// Sets `key` (flat, dotted or a whole law table) from a TOML value.
    pub fn set_value(&mut self, key: &str, value: &toml::Value) -> Result<()> {
        if key == "load" {
            let toml::Value::String(name) = value else {
                return Err(Error::invalid(key, value, &LOADS.join(", ")));
            };
            self.load = Load::named(name)?;
            return Ok(());
        }
        if let Some((table, name)) = key.split_once('.') {
            return self.set_law_key(table, name, value);
        }
        if LAW_TABLES.contains(&key) {
            let toml::Value::Table(entries) = value else {
                return Err(Error::invalid(key, value, "a table of law constants"));
            };
            if let Some(law) = entries.get("law") {
                self.set_law_key(key, "law", law)?;
            }
            for (name, v) in entries.iter().filter(|(name, _)| *name != "law") {
                self.set_law_key(key, name, v)?;
            }
            return Ok(());
        }
        let spec = table::spec(key).ok_or_else(|| unknown_parameter(key))?;
        match spec.kind {
            Kind::Flag { field, .. } => match value {
                toml::Value::Boolean(b) => *field(self) = *b,
                other => return Err(Error::invalid(key, other, "true or false")),
            },
            Kind::Number { field, .. } => {
                let x = number(key, value)?;
                match key {
                    "mu_l" => set_shear_modulus(&mut self.mu_l, &mut self.layer, x),
                    "mu_s" => set_shear_modulus(&mut self.mu_s, &mut self.substrate, x),
                    "mu_f" | "lambda_f" if self.fibres != FibreLaw::Quadratic => {
                        return Err(law_lacks(key, self.fibres.name(), self.fibres.constants()));
                    }
                    _ => *field(self) = x,
                }
            }
        }
        Ok(())
    }

    /// Sets `name` under the law table `table`.
    fn set_law_key(&mut self, table: &str, name: &str, value: &toml::Value) -> Result<()> {
        let key = format!("{table}.{name}");
        match table {
            "layer" | "substrate" => {
                let (mu_key, k_key) = if table == "layer" {
                    ("mu_l", "K_l")
                } else {
                    ("mu_s", "K_s")
                };
                let mu = self.number(mu_key)?;
                let law = if table == "layer" {
                    &mut self.layer
                } else {
                    &mut self.substrate
                };
                match (name, &*law) {
                    ("law", _) => {
                        let toml::Value::String(law_name) = value else {
                            return Err(Error::invalid(&key, value, &MATRIX_LAWS.join(", ")));
                        };
                        *law = MatrixLaw::named(&key, law_name, mu)?;
                    }
                    ("K", _) => return self.set_value(k_key, value),
                    ("mu", MatrixLaw::NeoHookean | MatrixLaw::Gent { .. }) => return self.set_value(mu_key, value),
                    _ => {
                        law.set_constant(table, name, value)?;
                        if let Some(implied) = law.implied_shear_modulus() {
                            *(if table == "layer" {
                                &mut self.mu_l
                            } else {
                                &mut self.mu_s
                            }) = implied;
                        }
                    }
                }
                Ok(())
            }
            "fibres" => match name {
                "law" => {
                    let toml::Value::String(law_name) = value else {
                        return Err(Error::invalid(&key, value, &FIBRE_LAWS.join(", ")));
                    };
                    self.fibres = FibreLaw::named(law_name)?;
                    Ok(())
                }
                "mu_f" | "lambda_f" | "tension_only" => self.set_value(name, value),
                _ => self.fibres.set_constant(name, value),
            },
            _ => Err(unknown_parameter(&key)),
        }
    }

    /// The `true`/`false` parameter called `key` ([`is_boolean`]).
    pub fn flag(&self, key: &str) -> Result<bool> {
        let key = if key == "fibres.tension_only" {
            "tension_only"
        } else {
            key
        };
        match table::spec(key).map(|s| &s.kind) {
            Some(Kind::Flag { field, .. }) => Ok(*field(&mut self.clone())),
            _ => Err(unknown_parameter(key)),
        }
    }

    /// The numeric parameter called `key`: a flat one, or a constant of a law in use
    /// (`layer.alpha` of a one-term Ogden layer, `fibres.k1`, ...).
    pub fn number(&self, key: &str) -> Result<f64> {
        let flat = match key {
            "layer.mu" if !matches!(self.layer, MatrixLaw::Ogden { .. }) => "mu_l",
            "substrate.mu" if !matches!(self.substrate, MatrixLaw::Ogden { .. }) => "mu_s",
            "layer.K" => "K_l",
            "substrate.K" => "K_s",
            "fibres.mu_f" => "mu_f",
            "fibres.lambda_f" => "lambda_f",
            other => other,
        };
        if matches!(flat, "mu_f" | "lambda_f") && self.fibres != FibreLaw::Quadratic {
            return Err(law_lacks(key, self.fibres.name(), self.fibres.constants()));
        }
        Ok(match table::spec(flat).map(|s| &s.kind) {
            Some(Kind::Number { field, .. }) => *field(&mut self.clone()),
            Some(Kind::Flag { .. }) => return Err(unknown_parameter(key)),
            None => match key.split_once('.') {
                Some(("layer", name)) if name != "law" => self.layer.number("layer", name)?,
                Some(("substrate", name)) if name != "law" => self.substrate.number("substrate", name)?,
                Some(("fibres", name)) if !matches!(name, "law" | "tension_only") => self.fibres.number(name)?,
                _ => return Err(unknown_parameter(key)),
            },
        })
    }

    /// The numeric keys [`Parameters::number`] accepts for the laws in use.
    pub fn numeric_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = parameter_names().map(String::from).collect();
        for (key, _) in self.law_entries() {
            if self.number(&key).is_ok() && !keys.contains(&key) {
                keys.push(key);
            }
        }
        keys.retain(|k| self.number(k).is_ok());
        keys
    }

    /// Every parameter as `(key, value)`: the flat keys, then each law table's `law` and own
    /// constants as dotted keys. Setting them in this order gives these parameters back.
    pub fn entries(&self) -> Vec<(String, toml::Value)> {
        let mut copy = self.clone();
        let mut entries: Vec<(String, toml::Value)> = TABLE
            .iter()
            .map(|s| {
                let value = match s.kind {
                    Kind::Flag { field, .. } => toml::Value::Boolean(*field(&mut copy)),
                    Kind::Number { field, .. } => toml::Value::Float(*field(&mut copy)),
                };
                (s.name.to_string(), value)
            })
            .collect();
        entries.push(("load".into(), toml::Value::String(self.load.name().into())));
        entries.extend(self.law_entries());
        entries
    }

    /// `law` and the own constants of each law table, as dotted keys.
    fn law_entries(&self) -> Vec<(String, toml::Value)> {
        let mut entries = Vec::new();
        let laws = [
            ("layer", self.layer.name(), self.layer.entries()),
            ("substrate", self.substrate.name(), self.substrate.entries()),
            ("fibres", self.fibres.name(), self.fibres.entries()),
        ];
        for (table, law, constants) in laws {
            entries.push((format!("{table}.law"), toml::Value::String(law.to_string())));
            entries.extend(constants.into_iter().map(|(name, v)| (format!("{table}.{name}"), v)));
        }
        entries
    }

    /// The larger of the layer's and the substrate's `K / mu`.
    pub fn bulk_to_shear_ratio(&self) -> f64 {
        (self.K_l / self.mu_l).max(self.K_s / self.mu_s)
    }

    /// Checks every range; the message names the parameter and its allowed range.
    pub fn validate(&self) -> Result<()> {
        table::validate(self)?;
        self.validate_load()?;
        self.layer.validate("layer", "mu_l", self.mu_l)?;
        self.substrate.validate("substrate", "mu_s", self.mu_s)?;
        self.fibres.validate()
    }

    /// A growth that is the load cannot also be fixed.
    fn validate_load(&self) -> Result<()> {
        let loaded: &[(&str, f64)] = match self.load {
            Load::Compression => &[],
            Load::Growth => &[("growth_layer", self.growth_layer)],
            Load::UniformGrowth => &[
                ("growth_layer", self.growth_layer),
                ("growth_substrate", self.growth_substrate),
            ],
        };
        for &(name, g) in loaded {
            if g != 1.0 {
                return Err(Error::invalid_number(
                    name,
                    g,
                    &format!("1 under load = {} (the load is that growth)", self.load.name()),
                ));
            }
        }
        Ok(())
    }

    /// The resolved set as TOML that `--params` reads back.
    pub fn to_toml(&self) -> String {
        let mut text = format!("{PHI_F_NOTE}\n");
        let mut current_table = String::new();
        for (key, value) in self.entries() {
            let name = match key.split_once('.') {
                Some((table, name)) => {
                    if table != current_table {
                        text.push_str(&format!("\n[{table}]\n"));
                        current_table = table.to_string();
                    }
                    name.to_string()
                }
                None => key,
            };
            match table::spec(&name) {
                Some(spec) => text.push_str(&format!("{name} = {value}  # {}\n", spec.meaning)),
                None => text.push_str(&format!("{name} = {value}\n")),
            }
        }
        text
    }
}

/// Read back from the summaries that serialise it (a map's restart file): the same keys and
/// tables as a parameters file, validated.
impl<'de> Deserialize<'de> for Parameters {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        let table = toml::Table::deserialize(deserializer)?;
        Parameters::from_table(&table).map_err(serde::de::Error::custom)
    }
}

/// Sets a shear modulus; a law whose constants fix it has them scaled to match.
fn set_shear_modulus(modulus: &mut f64, law: &mut MatrixLaw, value: f64) {
    if let Some(implied) = law.implied_shear_modulus().filter(|m| *m > 0.0) {
        law.scale_moduli(value / implied);
    }
    *modulus = value;
}

fn law_lacks(key: &str, law: &str, constants: &[&str]) -> Error {
    laws::not_a_constant(key, law, constants)
}

/// What `phi_f` means, written at the top of every parameter file (a TOML comment).
pub const PHI_F_NOTE: &str = "# phi_f is the volume fraction of EACH of the two fibre families (eq. 3 weights both \
    f(I4) terms by it).\n# The paper reads both ways: Table 1 gives phi_f = 0.1 next to phi_m = 0.9, the text \
    'phi_f = 0.05 for each family'.";

fn unknown_parameter(key: &str) -> Error {
    Error::UnknownParameter {
        name: key.to_string(),
        known: format!(
            "{}, and the law tables {} (e.g. layer.law = {}; fibres.law = {})",
            parameter_names().collect::<Vec<_>>().join(", "),
            LAW_TABLES.join(", "),
            MATRIX_LAWS.join(" | "),
            FIBRE_LAWS.join(" | ")
        ),
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

/// Parses a finite number given for `name`.
pub fn parse_number(name: &str, text: &str) -> Result<f64> {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(Error::invalid(name, text, "a finite number")),
    }
}

#[cfg(test)]
mod tests;
