//! Which way the first wrinkles run: onsets over the directions of the surface under biaxial
//! compression ([`crate::stability::oblique`]), and the polar figure of `d_c(k0, theta)`.

use crate::error::Result;
use crate::output::plot::{save_panels, Legend};
use crate::output::{CsvWriter, Figure, LineStyle, Series};
use crate::parameters::Parameters;
use crate::stability::{Method, Minimum, Onset, StabilityAnalysis, Surface};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// The modes an onset considers: the paper's plane strain (both `None`), or waves in the
/// surface under `d_3 = biaxial d`, along `theta` or along the most critical direction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Modes {
    /// `R = d_3 / d` in `[0, 1]` (absent: 0).
    pub biaxial: Option<f64>,
    /// A fixed wave direction in radians from X towards Z (absent: minimised over).
    pub theta: Option<f64>,
}

impl Modes {
    /// The surface analysis these modes ask for (`None`: plane strain).
    pub fn surface(&self) -> Option<Surface> {
        (self.biaxial.is_some() || self.theta.is_some()).then(|| Surface {
            biaxial: self.biaxial.unwrap_or(0.0),
            theta: self.theta.unwrap_or(0.0),
        })
    }

    /// An error naming `biaxial` or `theta` outside its range.
    pub fn validate(&self) -> Result<()> {
        self.surface().map_or(Ok(()), |s| s.validate())
    }

    /// The analysis of `params` by `method` for these modes.
    pub fn analysis(&self, params: &Parameters, method: Method) -> Result<StabilityAnalysis> {
        StabilityAnalysis::with_surface(params, method, self.surface())
    }

    /// These modes along one direction, as a dispersion curve takes them: in the surface without
    /// a `theta`, along X (`theta = 0`).
    pub fn along_one_direction(&self) -> Modes {
        Modes {
            theta: Some(self.theta.unwrap_or(0.0)).filter(|_| self.surface().is_some()),
            ..*self
        }
    }

    /// In words, for the terminal.
    pub fn describe(&self) -> String {
        match (self.surface(), self.theta) {
            (None, _) => "plane strain, waves along X".into(),
            (Some(s), Some(theta)) => format!("d_3 = {} d, waves along theta = {theta} rad", s.biaxial),
            (Some(s), None) => format!("d_3 = {} d, waves in every direction of the surface", s.biaxial),
        }
    }
}

/// An onset with the direction of its waves.
#[derive(Clone, Copy, Debug)]
pub struct DirectedOnset {
    pub onset: Onset,
    /// The wave vector's direction in `[0, pi)`: 0 in plane strain, the given `theta`, or the
    /// minimising one (NaN where no direction is preferred).
    pub theta0: f64,
    /// `max over theta` of the onset along `theta` minus `d_c` (only when minimised over theta).
    pub direction_spread: Option<f64>,
}

/// The onset of `params` for `modes`.
pub fn directed_onset(params: &Parameters, method: Method, modes: &Modes) -> Result<DirectedOnset> {
    let analysis = modes.analysis(params, method)?;
    match (modes.surface(), modes.theta) {
        (Some(_), None) => {
            let s = analysis.surface_onset()?;
            Ok(DirectedOnset {
                onset: s.onset,
                theta0: s.theta0,
                direction_spread: Some(s.direction_spread),
            })
        }
        (_, theta) => Ok(DirectedOnset {
            onset: analysis.onset()?,
            theta0: theta.unwrap_or(0.0),
            direction_spread: None,
        }),
    }
}

/// Directions of the polar figure: every 2.5 degrees of `[0, pi)`.
const POLAR_DIRECTIONS: usize = 72;

/// `d_c(k0, theta)` over `[0, pi)` at the onset's wavenumber, continued from one direction to
/// the next; written to `orientation.csv` (`theta,d_c`) and drawn (`orientation.png/svg`)
/// against `theta`, and as a polar curve of each direction's onset delay, with the onset's
/// direction and the fibres' projection on the surface. Nothing is drawn without an interior
/// `k0`.
pub fn orientation_figure(
    params: &Parameters,
    method: Method,
    modes: &Modes,
    directed: &DirectedOnset,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let onset = &directed.onset;
    if onset.minimum != Minimum::Interior || modes.surface().is_none() {
        return Ok(Vec::new());
    }
    let analysis = modes.analysis(params, method)?;
    let csv = out.join("orientation.csv");
    let mut table = CsvWriter::create(&csv, &["theta", "d_c"])?;
    let mut curve = Vec::with_capacity(POLAR_DIRECTIONS);
    let mut hint = Some(onset.d_c);
    for i in 0..POLAR_DIRECTIONS {
        let theta = i as f64 * PI / POLAR_DIRECTIONS as f64;
        let d_c = analysis.along(theta).critical_compression_near(onset.k0, hint)?;
        hint = Some(d_c);
        table.append(&[theta, d_c])?;
        curve.push((theta, d_c));
    }
    let lowest = curve.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let title = format!(
        "k0 = {:.3}, d_3 = {} d, beta = {:.1} deg, psi = {:.1} deg",
        onset.k0,
        modes.surface().map_or(0.0, |s| s.biaxial),
        params.beta.to_degrees(),
        params.psi.to_degrees()
    );
    let degrees = |theta: f64| theta.to_degrees();
    let (d_lo, d_hi) = (lowest, curve.iter().map(|p| p.1).fold(0.0, f64::max));
    let vertical = |angle: f64| {
        let a = degrees(angle.rem_euclid(PI));
        vec![(a, d_lo), (a, d_hi)]
    };
    let mut cartesian = Figure::new(
        format!("d_c(k0, theta), {title}"),
        "wave vector direction theta from X (deg)",
        "critical compression d_c",
    )
    .with_legend(Legend::UpperRight)
    .with(Series::new(
        "d_c(k0, theta)",
        curve.iter().map(|&(t, d)| (degrees(t), d)).collect(),
        LineStyle::Solid,
        0,
    ));
    // The onset delay of each direction, in per cent of the first onset, as a polar curve with
    // its conjugate half (theta + pi).
    let delay = |(theta, d): (f64, f64)| {
        let r = 100.0 * (d / lowest - 1.0);
        (r * theta.cos(), r * theta.sin())
    };
    let mut points: Vec<(f64, f64)> = curve.iter().map(|&p| delay(p)).collect();
    points.extend(curve.iter().map(|&(theta, d)| delay((theta + PI, d))));
    points.push(points[0]);
    let reach = (100.0 * (d_hi / lowest - 1.0)).max(1e-6) * 1.15;
    let ray = |angle: f64| {
        vec![
            (reach * angle.cos(), reach * angle.sin()),
            (-reach * angle.cos(), -reach * angle.sin()),
        ]
    };
    let mut polar = Figure::new(
        "Onset delay of each direction (%)",
        "delay x cos theta (%)",
        "delay x sin theta (%)",
    )
    .with_legend(Legend::UpperRight)
    .with(Series::new("100 (d_c / min d_c - 1)", points, LineStyle::Solid, 0));
    if directed.theta0.is_finite() {
        let label = format!("first wrinkles: theta0 = {:.1} deg", degrees(directed.theta0));
        cartesian = cartesian.with(Series::new(
            label.clone(),
            vertical(directed.theta0),
            LineStyle::Dashed,
            1,
        ));
        polar = polar.with(Series::new(label, ray(directed.theta0), LineStyle::Dashed, 1));
    }
    if params.phi_f > 0.0 && params.beta.cos().abs() > 1e-12 {
        let label = format!("fibres' projection: psi = {:.1} deg", degrees(params.psi));
        cartesian = cartesian.with(Series::new(label.clone(), vertical(params.psi), LineStyle::Dashed, 2));
        polar = polar.with(Series::new(label, ray(params.psi), LineStyle::Dashed, 2));
    }
    // The panel's plotting area is about 1.45 times as wide as it is high: equal scales.
    polar.x_range = Some((-1.45 * reach, 1.45 * reach));
    polar.y_range = Some((-reach, reach));
    let mut files = vec![csv];
    files.extend(save_panels(&[cartesian, polar], out, "orientation")?);
    Ok(files)
}
