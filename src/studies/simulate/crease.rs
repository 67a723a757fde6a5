//! What a run to a crease writes besides the amplitude: the contact pressure of the VTU
//! snapshots, and `contact.json` (the contact and stabilisation columns of `amplitude.csv` are
//! among [`super::columns::AMPLITUDE_COLUMNS`]).

use crate::output::vtu::DataArray;
use crate::protocol::StepRecord;
use serde::Serialize;

/// Nominal contact pressure at every node of a mesh of `nodes` nodes (zero off the surface).
pub fn pressure_array(record: Option<&StepRecord>, nodes: usize) -> DataArray {
    let mut values = vec![0.0; nodes];
    for &(node, p) in record
        .and_then(|r| r.augmented.as_ref())
        .map_or(&[][..], |a| &a.pressure)
    {
        values[node] = p;
    }
    DataArray::scalars("contact_pressure", values)
}

/// `contact.json`: where the surface first touched (a plane or itself) and how far it zipped up.
#[derive(Clone, Debug, Serialize)]
pub struct ContactReport {
    /// First `d` with a loaded contact pair; `None` if the surface never touched.
    pub d_first_contact: Option<f64>,
    /// Deformed length of the closed surface at the last state.
    pub contact_length_final: f64,
    /// Number of separate closed zones at the last state.
    pub contact_zones_final: usize,
    pub d_reached: f64,
    /// Largest penetration of any accepted state (tolerance `1e-3 H`).
    pub penetration_max: f64,
    /// Dissipated over strain energy at the last state, and its largest value.
    pub stabilisation_energy_fraction_final: f64,
    pub stabilisation_energy_fraction_max: f64,
    /// Energy dissipated by the stabilisation along the path.
    pub dissipated_energy: f64,
    /// Smallest `J` at a Gauss point over all accepted states.
    pub min_jacobian: f64,
    pub note: &'static str,
}

const CONTACT_NOTE: &str = "contact_length is the deformed length of surface whose nodes are pressed, counted once \
    against a symmetry plane and half against the surface itself (both flanks of a closed trough carry pressure), \
    summed over all zones. Pressures in the VTU are nominal: contact force per reference length of surface.";

impl ContactReport {
    /// The report of the accepted states `records` (the last one is the final state).
    pub fn new(records: &[StepRecord]) -> Self {
        let augmented = || records.iter().filter_map(|r| r.augmented.as_ref());
        let last = records.last().and_then(|r| r.augmented.clone()).unwrap_or_default();
        ContactReport {
            d_first_contact: records
                .iter()
                .find(|r| r.augmented.as_ref().is_some_and(|a| a.in_contact))
                .map(|r| r.d),
            contact_length_final: last.contact_length,
            contact_zones_final: last.contact_zones,
            d_reached: records.last().map_or(0.0, |r| r.d),
            penetration_max: augmented().fold(0.0, |m, a| m.max(a.penetration)),
            stabilisation_energy_fraction_final: last.stabilisation_energy_fraction,
            stabilisation_energy_fraction_max: augmented().fold(0.0, |m, a| m.max(a.stabilisation_energy_fraction)),
            dissipated_energy: last.dissipated_energy,
            min_jacobian: records.iter().fold(f64::INFINITY, |m, r| m.min(r.min_jacobian)),
            note: CONTACT_NOTE,
        }
    }
}
