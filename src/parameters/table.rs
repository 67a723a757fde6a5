//! The flat parameters, one row each: name, Table 1 default, allowed range, units and meaning.
//! The defaults, the validator, `--set`, the comments of a parameters file, the command line's
//! help and the map's axes all read this table.

use super::Parameters;
use crate::error::{Error, Result};

/// Smallest and largest moduli accepted (units of `mu_s`): K/mu = 1e6 is nearly incompressible
/// tissue; beyond 1e12 the energy's derivatives lose all precision.
pub const MODULUS_MIN: f64 = 1e-12;
pub const MODULUS_MAX: f64 = 1e12;

/// One flat parameter.
pub struct Spec {
    pub name: &'static str,
    pub kind: Kind,
    /// What it is, with its units.
    pub meaning: &'static str,
}

/// A number with its default and range, or a switch with its default.
pub enum Kind {
    Number {
        default: f64,
        range: Range,
        field: fn(&mut Parameters) -> &mut f64,
    },
    Flag {
        default: bool,
        field: fn(&mut Parameters) -> &mut bool,
    },
}

/// The allowed values of a number.
#[derive(Clone, Copy)]
pub enum Range {
    /// A shear modulus in `[1e-12, 1e12]`.
    Modulus,
    /// A bulk modulus in `[1e-12, 1e12]` (beyond it: exact incompressibility).
    BulkModulus,
    /// A stiffness in `[0, 1e12]`.
    Stiffness,
    /// A fraction in `[0, 1]`.
    Fraction,
    /// A stretch in `(0, 10]`.
    Stretch,
    /// Any finite angle.
    Angle,
    /// A growth stretch in `[0.1, 10]`.
    Growth,
}

impl Range {
    pub fn contains(self, x: f64) -> bool {
        x.is_finite()
            && match self {
                Range::Modulus | Range::BulkModulus => (MODULUS_MIN..=MODULUS_MAX).contains(&x),
                Range::Stiffness => (0.0..=MODULUS_MAX).contains(&x),
                Range::Fraction => (0.0..=1.0).contains(&x),
                Range::Stretch => x > 0.0 && x <= 10.0,
                Range::Angle => true,
                Range::Growth => (0.1..=10.0).contains(&x),
            }
    }

    /// The range in a few characters, for the help.
    pub fn short(self) -> &'static str {
        match self {
            Range::Modulus | Range::BulkModulus => "[1e-12, 1e12]",
            Range::Stiffness => "[0, 1e12]",
            Range::Fraction => "[0, 1]",
            Range::Stretch => "(0, 10]",
            Range::Angle => "finite",
            Range::Growth => "[0.1, 10]",
        }
    }

    pub fn describe(self) -> &'static str {
        match self {
            Range::Modulus => "a finite number in [1e-12, 1e12] (moduli in units of mu_s)",
            Range::BulkModulus => {
                "a finite number in [1e-12, 1e12] (moduli in units of mu_s; for exactly incompressible layers set incompressible = true)"
            }
            Range::Stiffness => "[0, 1e12] (in units of mu_s)",
            Range::Fraction => "[0, 1]",
            Range::Stretch => "(0, 10]",
            Range::Angle => "a finite angle in radians",
            Range::Growth => "a growth stretch in [0.1, 10] (1: no growth)",
        }
    }
}

const fn number(
    name: &'static str,
    default: f64,
    range: Range,
    field: fn(&mut Parameters) -> &mut f64,
    meaning: &'static str,
) -> Spec {
    Spec {
        name,
        kind: Kind::Number { default, range, field },
        meaning,
    }
}

const fn flag(
    name: &'static str,
    default: bool,
    field: fn(&mut Parameters) -> &mut bool,
    meaning: &'static str,
) -> Spec {
    Spec {
        name,
        kind: Kind::Flag { default, field },
        meaning,
    }
}

/// The flat parameters in the order they are printed, with the paper's Table 1 as defaults.
pub const TABLE: [Spec; 15] = [
    number("mu_l", 10.0, Range::Modulus, |p| &mut p.mu_l, "shear modulus of the layer, whatever its law (units of mu_s)"),
    number("K_l", 30.0, Range::BulkModulus, |p| &mut p.K_l, "bulk modulus of the layer (units of mu_s)"),
    number("mu_s", 1.0, Range::Modulus, |p| &mut p.mu_s, "shear modulus of the substrate matrix, the unit of stress"),
    number("K_s", 3.0, Range::BulkModulus, |p| &mut p.K_s, "bulk modulus of the substrate matrix (units of mu_s)"),
    number("phi_m", 0.9, Range::Fraction, |p| &mut p.phi_m, "volume fraction of the substrate matrix"),
    number(
        "phi_f",
        0.1,
        Range::Fraction,
        |p| &mut p.phi_f,
        "volume fraction of EACH of the two fibre families (Table 1's 0.1 read as eq. 3 does; the paper's text says 0.05 per family)",
    ),
    number("mu_f", 10.0, Range::Stiffness, |p| &mut p.mu_f, "stiffness of the quadratic fibres (units of mu_s)"),
    number("lambda_f", 1.0, Range::Stretch, |p| &mut p.lambda_f, "pre-stretch parameter of the quadratic fibres"),
    number(
        "beta",
        0.0,
        Range::Angle,
        |p| &mut p.beta,
        "fibre inclination from the surface (radians): families along (cos beta, +-sin beta) in the X-Y plane",
    ),
    number(
        "psi",
        0.0,
        Range::Angle,
        |p| &mut p.psi,
        "fibre azimuth in the surface plane, from X towards Z (radians): families along (cos beta cos psi, +-sin beta, cos beta sin psi)",
    ),
    flag(
        "tension_only",
        false,
        |p| &mut p.tension_only,
        "fibres carry no load in compression (I4 < lambda_f^2; HGO: E < 0)",
    ),
    flag(
        "incompressible",
        false,
        |p| &mut p.incompressible,
        "both layers exactly incompressible (J = 1; K_l, K_s unused; finite elements need --element mixed)",
    ),
    number(
        "growth_layer",
        1.0,
        Range::Growth,
        |p| &mut p.growth_layer,
        "growth of the layer, F = Fe Fg (1 under load = growth, whose load it is)",
    ),
    number("growth_substrate", 1.0, Range::Growth, |p| &mut p.growth_substrate, "growth of the substrate"),
    flag(
        "area_growth",
        false,
        |p| &mut p.area_growth,
        "the thickness grows as the length does, Fg = diag(g, g, g3); false: Fg = diag(g, 1, g3) (g3 = 1 in plane strain, 1/(1 - R d) on a patch under biaxiality R)",
    ),
];

/// The row of `name`.
pub fn spec(name: &str) -> Option<&'static Spec> {
    TABLE.iter().find(|s| s.name == name)
}

/// Checks the flat numbers of `p` against their ranges.
pub fn validate(p: &Parameters) -> Result<()> {
    let mut copy = p.clone();
    for s in &TABLE {
        if let Kind::Number { range, field, .. } = s.kind {
            let x = *field(&mut copy);
            if !range.contains(x) {
                return Err(Error::invalid_number(s.name, x, range.describe()));
            }
        }
    }
    Ok(())
}

/// The table as the command line shows it (`fiberfold params --help`): every key of `--set`
/// with its default, range and meaning, one per line, then the laws and the loads.
pub fn help() -> String {
    let rows: Vec<String> = TABLE
        .iter()
        .map(|s| match s.kind {
            Kind::Number { default, range, .. } => {
                format!("  {} = {default}, in {}: {}", s.name, range.short(), s.meaning)
            }
            Kind::Flag { default, .. } => format!("  {} = {default}: {}", s.name, s.meaning),
        })
        .collect();
    format!(
        "Keys of --set (e.g. `--set beta=0.785398 --set mu_f=20`), with their defaults and ranges:\n{}\n\n\
         Laws, by dotted keys (the guide's \"Your own tissue\"); set a law before its constants:\n  \
         layer.law, substrate.law = neo_hookean (default) | mooney_rivlin (layer.c1, layer.c2) | ogden \
         (layer.mu, layer.alpha: numbers or lists [..] of 1 to 3 terms) | gent (layer.jm); mu_l, mu_s stay \
         each law's shear modulus and K_l, K_s its bulk modulus\n  \
         fibres.law = quadratic (default: mu_f, lambda_f) | hgo (fibres.k1, fibres.k2, fibres.kappa in \
         [0, 1/3], default 0)\n  \
         e.g. `--set layer.law=ogden --set layer.alpha=-25`\n\n\
         Loads: load = compression (default: the end-shortening d) | growth (the layer's growth g from 1, \
         ends held) | uniform_growth (both layers grow by g, ends held).",
        rows.join("\n")
    )
}
