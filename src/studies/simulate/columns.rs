//! The columns of `amplitude.csv`, one entry each: its name and how a converged state's
//! [`StepRecord`] gives its value. The header and every row come from [`AMPLITUDE_COLUMNS`].

use crate::output::table::{self, Column};
use crate::protocol::StepRecord;

/// 1 for `true`, 0 for `false`.
fn flag(set: bool) -> f64 {
    f64::from(u8::from(set))
}

/// A contact or stabilisation value of a step (zero without contact or stabilisation).
fn augmented(record: &StepRecord, value: fn(&crate::protocol::AugmentedRecord) -> f64) -> f64 {
    record.augmented.as_ref().map_or(0.0, value)
}

/// Every column of `amplitude.csv`, in order.
pub const AMPLITUDE_COLUMNS: [Column<StepRecord>; 16] = [
    Column {
        name: "d",
        value: |r| r.d,
    },
    // The wrinkle amplitude `A = (max y - min y) / 2` of the top surface.
    Column {
        name: "A",
        value: |r| r.amplitude,
    },
    Column {
        name: "strain_energy",
        value: |r| r.strain_energy,
    },
    Column {
        name: "newton_iterations",
        value: |r| r.iterations as f64,
    },
    Column {
        name: "residual",
        value: |r| *r.residual_history.last().expect("non-empty"),
    },
    Column {
        name: "min_J",
        value: |r| r.min_jacobian,
    },
    Column {
        name: "step_seconds",
        value: |r| r.seconds,
    },
    // Contact and stabilisation of a run to a crease.
    Column {
        name: "in_contact",
        value: |r| augmented(r, |a| flag(a.in_contact)),
    },
    Column {
        name: "contact_length",
        value: |r| augmented(r, |a| a.contact_length),
    },
    Column {
        name: "penetration",
        value: |r| augmented(r, |a| a.penetration),
    },
    Column {
        name: "stabilisation_energy_fraction",
        value: |r| augmented(r, |a| a.stabilisation_energy_fraction),
    },
    // 1 where a snap reached the state.
    Column {
        name: "snap",
        value: |r| flag(r.snap.is_some()),
    },
    // 1 where the energy's minimisation from the predictor corrected the step after Newton's
    // iteration failed.
    Column {
        name: "minimised",
        value: |r| flag(r.minimised),
    },
    // The smallest strong-ellipticity margin of each layer over its Gauss points.
    Column {
        name: "ellipticity_layer",
        value: |r| r.ellipticity.layer,
    },
    Column {
        name: "ellipticity_substrate",
        value: |r| r.ellipticity.substrate,
    },
    // The layer's growth `g` (the load under growth; 1 without growth).
    Column {
        name: "growth_layer",
        value: |r| r.growth_layer,
    },
];

/// The header of `amplitude.csv`.
pub fn amplitude_header() -> Vec<&'static str> {
    table::header(&AMPLITUDE_COLUMNS)
}

/// One accepted step as a row of `amplitude.csv`.
pub fn amplitude_row(record: &StepRecord) -> Vec<f64> {
    table::row(&AMPLITUDE_COLUMNS, record)
}
