//! What loads the bilayer: the end-shortening or a growth (`docs/model.md`, "Growth").

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// What loads the bilayer (`docs/model.md`, "Growth"). Every analysis follows one load
/// parameter; the linear theory searches it through the strain `d`: `d = 1 - lambda_1` under
/// compression and `d = 1 - 1/g` under growth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Load {
    /// The end-shortening `d = 1 - lambda_1` of both layers (the paper's load).
    #[default]
    Compression,
    /// The layer's growth `g` from 1 upwards, with the ends held (`lambda_1 = 1`): differential
    /// growth on a substrate that grows by `growth_substrate` only.
    Growth,
    /// Both layers growing by `g`, with the ends held: the grown body compressed by `1/g`.
    UniformGrowth,
}

/// The names of the loads, as `load` takes them.
pub const LOADS: [&str; 3] = ["compression", "growth", "uniform_growth"];

impl Load {
    pub fn name(self) -> &'static str {
        LOADS[self as usize]
    }

    pub fn named(name: &str) -> Result<Self> {
        match name {
            "compression" => Ok(Load::Compression),
            "growth" => Ok(Load::Growth),
            "uniform_growth" => Ok(Load::UniformGrowth),
            other => Err(Error::invalid("load", other, &LOADS.join(", "))),
        }
    }

    /// Whether the load is a growth (its parameter is `g`, not `d`).
    pub fn is_growth(self) -> bool {
        self != Load::Compression
    }

    /// The load parameter at the strain `d` of the searches: `d` itself, or `g = 1/(1 - d)`.
    pub fn parameter(self, d: f64) -> f64 {
        if self.is_growth() {
            1.0 / (1.0 - d)
        } else {
            d
        }
    }

    /// How far the sides have moved in at the strain `d`, as a fraction of their distance: `d`
    /// under compression, 0 under growth (the sides are held).
    pub fn end_shortening(self, d: f64) -> f64 {
        if self.is_growth() {
            0.0
        } else {
            d
        }
    }

    /// The name of the load parameter, as in CSV and JSON columns.
    pub fn parameter_name(self) -> &'static str {
        if self.is_growth() {
            "g"
        } else {
            "d"
        }
    }
}
