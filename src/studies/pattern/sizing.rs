//! The patch's size: the theory's onset mode's period along each side, times `--periods`, a side
//! whose period is longer than `--max-side` wavelengths held to one wavelength per period.

use super::PatternStudy;
use crate::error::{Error, Result};
use crate::mesh::{PatchSpec, Sides};
use crate::parameters::Parameters;
use crate::stability::{Method, StabilityAnalysis, Surface, SurfaceOnset};
use serde::Serialize;

/// [`PatternStudy::max_side`]'s default: an onset direction within 14.5 deg of an axis is held
/// along it.
pub(super) fn default_max_side() -> f64 {
    4.0
}

/// A side the onset mode's period along it did not fit ([`PatternStudy::max_side`]): one onset
/// wavelength per period, so that the theory's wave vector is not admissible and the patch holds
/// the nearest ones (`d_c_admissible` above the theory's `d_c`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CappedSide {
    /// `"X"` or `"Z"`.
    pub side: &'static str,
    /// The onset mode's period along it (H), which holding its wave vector would take.
    pub period: f64,
    /// That period in onset wavelengths: the `max_side` that holds it.
    pub wavelengths: f64,
}

/// The patch of `study` for `params`: the theory's onset, the patch that holds it and the sides
/// too long for [`PatternStudy::max_side`].
pub fn size_patch(params: &Parameters, study: &PatternStudy) -> Result<(SurfaceOnset, PatchSpec, Vec<CappedSide>)> {
    for (name, count, least) in [
        ("periods", study.periods, 1),
        ("elements-per-wavelength", study.elements_per_wavelength, 2),
    ] {
        if count < least {
            return Err(Error::invalid(name, count, &format!("an integer >= {least}")));
        }
    }
    for (name, count) in [
        ("layer-elements", study.layer_elements),
        ("substrate-elements", study.substrate_elements),
    ] {
        if count < 1 {
            return Err(Error::invalid(name, count, "an integer >= 1"));
        }
    }
    if study.max_side.is_nan() || study.max_side < 1.0 {
        return Err(Error::invalid(
            "max-side",
            study.max_side,
            "[1, inf] onset wavelengths per period",
        ));
    }
    if !(study.depth_wavelengths.is_finite() && study.depth_wavelengths > 0.0) {
        return Err(Error::invalid("depth", study.depth_wavelengths, "(0, inf) wavelengths"));
    }
    if study.sides == Sides::Symmetry && params.psi != 0.0 {
        return Err(Error::invalid(
            "sides",
            "symmetry",
            "periodic when psi != 0 under a load that singles out X (R != 1 or a prestrain): the sides are then planes of the fibres' symmetry only for psi = 0",
        ));
    }
    let surface = Surface {
        biaxial: study.biaxial,
        theta: 0.0,
    };
    let onset = StabilityAnalysis::with_surface(params, Method::Exact, Some(surface))?.surface_onset()?;
    let wavelength = onset.onset.wavelength().ok_or_else(|| {
        Error::invalid(
            "parameters",
            format!("an onset with minimum {:?}", onset.onset.minimum),
            "parameters whose onset has a finite wavelength (an interior minimum of d_c(k))",
        )
    })?;
    // The onset mode's period along each side: lambda / |cos theta0| along X, lambda / |sin
    // theta0| along Z; one wavelength along a side the mode runs along, or nearly along (a
    // period longer than max_side wavelengths: the box would grow without bound as theta0
    // nears an axis).
    let theta = if onset.theta0.is_nan() { 0.0 } else { onset.theta0 };
    let mut capped = Vec::new();
    let mut along = |side: &'static str, c: f64| {
        let period = wavelength / c.abs();
        if c.abs() < 1e-6 {
            wavelength
        } else if period > study.max_side * wavelength {
            capped.push(CappedSide {
                side,
                period,
                wavelengths: period / wavelength,
            });
            wavelength
        } else {
            period
        }
    };
    let periods = study.periods as f64;
    let (length_x, length_z) = (periods * along("X", theta.cos()), periods * along("Z", theta.sin()));
    let elements = |length: f64| {
        let n = (length / wavelength * study.elements_per_wavelength as f64 - 1e-9).ceil() as usize;
        n.max(2)
    };
    let depth = study.depth_wavelengths * wavelength;
    let h0 = study.top_substrate_thickness;
    let feasible = match study.substrate_elements {
        1 => (h0 - depth).abs() <= 1e-12 * depth,
        _ => h0.is_finite() && h0 > 0.0 && h0 < depth,
    };
    if !feasible {
        return Err(Error::invalid(
            "h0",
            h0,
            &format!("(0, {depth:.4}), the substrate's depth (= it for one substrate element)"),
        ));
    }
    let spec = PatchSpec {
        nx: elements(length_x),
        nz: elements(length_z),
        length_x,
        length_z,
        layer_elements: study.layer_elements,
        substrate_elements: study.substrate_elements,
        top_substrate_thickness: study.top_substrate_thickness,
        depth,
        sides: study.sides,
        element: study.element,
    };
    spec.validate()?;
    Ok((onset, spec, capped))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stability::oblique::box_modes;

    #[test]
    fn a_side_longer_than_max_side_holds_the_nearest_wave_vector() {
        // Fibres in the surface at 30 deg under d_3 = d / 2: the onset's wave vector lies about
        // one degree from X, and the mode's period along Z is some sixty wavelengths.
        let params = Parameters {
            beta: 0.0,
            psi: 30f64.to_radians(),
            ..Parameters::default()
        };
        let study = PatternStudy {
            biaxial: 0.5,
            ..PatternStudy::default()
        };
        let (onset, spec, capped) = size_patch(&params, &study).unwrap();
        let (wavelength, theta0) = (onset.onset.wavelength().unwrap(), onset.theta0);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert_eq!(capped.len(), 1);
        assert_eq!(capped[0].side, "Z");
        assert!(close(capped[0].period, wavelength / theta0.sin().abs()));
        assert!(capped[0].period > study.max_side * wavelength);
        assert!(close(capped[0].wavelengths * wavelength, capped[0].period));
        assert!(close(spec.length_z, wavelength) && close(spec.length_x, wavelength / theta0.cos().abs()));
        // Without the cap the patch is the mode's own, and holds it.
        let whole = PatternStudy {
            max_side: f64::INFINITY,
            ..study
        };
        let (_, long, none) = size_patch(&params, &whole).unwrap();
        assert!(none.is_empty() && close(long.length_z, capped[0].period));
        // Capped, the nearest admissible wave vector runs along X, and the theory's d_c there is
        // above the onset's, by what the direction's degree costs.
        let modes = box_modes(
            &params,
            Method::Exact,
            0.5,
            (spec.length_x, spec.length_z),
            3.0 * onset.onset.k0,
        )
        .unwrap();
        let nearest = modes[0];
        assert_eq!(nearest.n, 0);
        let excess = nearest.d_c - onset.onset.d_c;
        assert!(
            (0.0..1e-4).contains(&excess),
            "d_c {} against the onset's {}",
            nearest.d_c,
            onset.onset.d_c
        );
        // Table 1's oblique pair (36 deg) needs no cap.
        let in_surface = Parameters {
            beta: 0.0,
            ..Parameters::default()
        };
        let (_, _, pair) = size_patch(&in_surface, &PatternStudy::default()).unwrap();
        assert!(pair.is_empty());
        let mut wide = study;
        wide.max_side = 0.5;
        assert!(size_patch(&params, &wide).unwrap_err().to_string().contains("max-side"));
    }
}
