//! What is worth recording of a converged state besides the solver's own facts, each taken by a
//! [`Measure`] that the path is given: the wrinkle amplitude of the top surface, the
//! strong-ellipticity margins of the layers, the layer's growth. The continuation itself knows
//! nothing of the bilayer.

use super::load_path::Loading;
use super::record::StepRecord;
use super::surface::amplitude;
use crate::error::Result;
use crate::fem::ellipticity::ellipticity_margins;
use crate::fem::System;

/// A quantity of a converged state of a system `S`, written into its record.
pub trait Measure<S = System>: Send + Sync {
    /// Writes what it measures of the converged state `u` of `system` into `record`.
    fn measure(&self, system: &S, u: &[f64], record: &mut StepRecord) -> Result<()>;
}

/// The wrinkle amplitude `A = (max y - min y) / 2` of the top surface ([`StepRecord::amplitude`]).
pub struct SurfaceAmplitude;

impl Measure for SurfaceAmplitude {
    fn measure(&self, system: &System, u: &[f64], record: &mut StepRecord) -> Result<()> {
        record.amplitude = amplitude(system.mesh(), u);
        Ok(())
    }
}

/// The smallest strong-ellipticity margin of each layer over its Gauss points
/// ([`StepRecord::ellipticity`]).
pub struct Ellipticity;

impl Measure for Ellipticity {
    fn measure(&self, system: &System, u: &[f64], record: &mut StepRecord) -> Result<()> {
        record.ellipticity = ellipticity_margins(system, u)?;
        Ok(())
    }
}

/// The layer's growth `g` along `X` at the state's load ([`StepRecord::growth_layer`]).
pub struct LayerGrowth;

impl Measure for LayerGrowth {
    fn measure(&self, system: &System, _u: &[f64], record: &mut StepRecord) -> Result<()> {
        record.growth_layer = system.layer_growth();
        Ok(())
    }
}

/// The bilayer's measures: amplitude, ellipticity, growth.
pub fn bilayer_measures() -> Vec<Box<dyn Measure>> {
    vec![Box::new(SurfaceAmplitude), Box::new(Ellipticity), Box::new(LayerGrowth)]
}

/// Takes every measure of `measures` of the state `u` of `system` into `record`.
pub fn measure_all<S>(measures: &[Box<dyn Measure<S>>], system: &S, u: &[f64], record: &mut StepRecord) -> Result<()> {
    measures.iter().try_for_each(|m| m.measure(system, u, record))
}
