//! Critical compression `d_c(k)` (smallest root in `d`), onset `k0 = argmin d_c(k)`, and the
//! compression at which strong ellipticity is lost.

use super::discrete;
use super::ellipticity::ellipticity_margin;
use super::exact::{bifurcation_determinant, surface_impedance, LayerSolutions};
use super::surface::Surface;
use super::{IncrementalModuli, Method};
use crate::error::{Error, Result};
use crate::homogeneous::{constraint_pressure, homogeneous_state};
use crate::material::{Bilayer, StrainEnergy};
use crate::numerics::minimize::brent_minimize;
use crate::numerics::roots::brent;
use crate::parameters::Parameters;
use serde::{Deserialize, Serialize};

/// Largest compression searched (`d` in `(0, D_END]`).
pub const D_END: f64 = 0.95;
/// Smallest compression evaluated (the reference side of every sign test).
const D_START: f64 = 1e-6;
/// Tolerance of `d_c` in `d`.
const D_TOLERANCE: f64 = 1e-13;
/// The longest step of the scan for the loss of ellipticity.
const ELLIPTICITY_STEP: f64 = 0.1;

/// Where the smallest `d_c(k)` lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Minimum {
    /// At a finite `k0 > 0`: wrinkles of wavelength `2 pi / k0`.
    Interior,
    /// `d_c(k)` decreases all the way to `k -> 0`: the layer is too soft to set a wavelength and
    /// the substrate's own surface instability comes first (`k0 = 0`, `d_c` its limit).
    LongWave,
    /// `d_c(k)` decreases all the way to `k -> inf`: the layer's own surface instability comes
    /// first, at wavelengths much shorter than `H` (`k0 = inf`, `d_c` its limit).
    ShortWave,
    /// `d_c(k)` is the same at every `k` (within `RISE_TOLERANCE` over the grid): no contrast
    /// between the layers, the half-space's scale-free surface instability (`k0` undefined: NaN,
    /// `null` in JSON).
    Flat,
}

/// Wavenumbers probed for the long-wave limit (down to `K_LONG`) and the short-wave limit (up
/// to `K_SHORT`, where `kH` is large enough for the layer to act as a half-space and the exact
/// method is still well conditioned); a minimum still at either end is reported as the limit.
const K_LONG: f64 = 1e-4;
const K_SHORT: f64 = K_MAX;
/// Largest wavenumber analysed: beyond `kH = 10` the layer acts as a half-space (a nearly
/// incompressible neo-Hookean layer's `d_c` is Biot's to 2e-10 there).
pub const K_MAX: f64 = 10.0;
/// Probes per decade beyond the grid.
const PROBES_PER_DECADE: f64 = 4.0;
/// A rise of `d_c` beyond the grid smaller than this is the round-off of a curve that has
/// levelled off at its limit, not a minimum.
pub(super) const RISE_TOLERANCE: f64 = 1e-6;

/// The onset of wrinkling: the minimum of `d_c(k)`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Onset {
    /// Onset wavenumber (referential, units 1/H): 0 for a long-wave, infinite for a short-wave
    /// minimum and NaN for a flat curve (both `null` in JSON).
    pub k0: f64,
    /// Critical compression at `k0`.
    pub d_c: f64,
    /// `1 - d_c`.
    pub lambda1_c: f64,
    /// Compression at which either layer loses strong ellipticity (None if not before 0.95).
    pub d_ellipticity_loss: Option<f64>,
    /// Compression at which the homogeneous state leaves a law's domain (a Gent law's limiting
    /// extensibility; None if not before 0.95): the search ends there.
    pub d_domain_end: Option<f64>,
    /// Whether the minimum is interior or a limit.
    pub minimum: Minimum,
}

impl Onset {
    /// The wavelength `2 pi / k0` of an interior minimum.
    pub fn wavelength(&self) -> Option<f64> {
        (self.minimum == Minimum::Interior).then(|| 2.0 * std::f64::consts::PI / self.k0)
    }
}

/// The stability analysis of one parameter set.
#[derive(Clone, Debug)]
pub struct StabilityAnalysis {
    pub(super) materials: Bilayer,
    pub(super) method: Method,
    /// Searches stop here: 0.95, the end of a law's domain or the loss of ellipticity,
    /// whichever comes first.
    d_limit: f64,
    d_ellipticity_loss: Option<f64>,
    /// Where the homogeneous state leaves a law's domain (a Gent law's limiting extensibility).
    d_domain_end: Option<f64>,
    /// Wavenumber range of the onset search.
    pub k_range: (f64, f64),
    /// Modes in a direction of the surface under biaxial compression; `None` is the paper's
    /// plane strain (modes along X, no Z displacement).
    pub(super) surface: Option<Surface>,
}

impl StabilityAnalysis {
    /// Sets up the analysis (validates the parameters, finds the loss of ellipticity).
    pub fn new(params: &Parameters, method: Method) -> Result<Self> {
        Self::with_surface(params, method, None)
    }

    /// The analysis of modes along `surface.theta` under biaxial compression (or of plane
    /// strain, `None`).
    pub fn with_surface(params: &Parameters, method: Method, surface: Option<Surface>) -> Result<Self> {
        params.validate()?;
        if let Some(s) = &surface {
            s.validate()?;
        }
        let mut analysis = StabilityAnalysis {
            materials: Bilayer::new(params),
            method,
            d_limit: D_END,
            d_ellipticity_loss: None,
            d_domain_end: None,
            k_range: (0.02, 5.0),
            surface,
        };
        analysis.d_domain_end = analysis.find_domain_end()?;
        analysis.d_ellipticity_loss = analysis.find_ellipticity_loss()?;
        analysis.d_limit = analysis.d_ellipticity_loss.or(analysis.d_domain_end).unwrap_or(D_END);
        Ok(analysis)
    }

    /// Compression at which either layer first loses strong ellipticity (None below 0.95).
    pub fn ellipticity_loss(&self) -> Option<f64> {
        self.d_ellipticity_loss
    }

    /// Incremental moduli of layer and substrate at the homogeneous state of compression `d`.
    pub fn moduli(&self, d: f64) -> Result<(IncrementalModuli, IncrementalModuli)> {
        let state = homogeneous_state(&self.materials, d)?;
        let (layer, substrate) = (state.layer_gradient(), state.substrate_gradient());
        let (loaded, _) = self.materials.at_load(d);
        if self.materials.incompressible {
            let (l, s) = (&loaded.layer, &loaded.substrate);
            return Ok((
                IncrementalModuli::incompressible(l, &layer, constraint_pressure(l, &layer)?)?,
                IncrementalModuli::incompressible(s, &substrate, constraint_pressure(s, &substrate)?)?,
            ));
        }
        Ok((
            IncrementalModuli::at(&loaded.layer, &layer)?,
            IncrementalModuli::at(&loaded.substrate, &substrate)?,
        ))
    }

    /// The first `d` at which the homogeneous state leaves a law's domain (None before 0.95,
    /// and where neither law's domain is bounded).
    fn find_domain_end(&self) -> Result<Option<f64>> {
        if !(self.materials.layer.bounded_domain() || self.materials.substrate.bounded_domain()) {
            return Ok(None);
        }
        let moduli = |d: f64| match self.surface {
            Some(_) => self.surface_moduli(d).map(|_| ()),
            None => homogeneous_state(&self.materials, d).and_then(|_| self.moduli(d).map(|_| ())),
        };
        let admissible = |d: f64| match moduli(d) {
            Ok(_) => Ok(true),
            Err(Error::BeyondExtensibility { .. }) => Ok(false),
            Err(e) => Err(e),
        };
        let mut lo = D_START;
        for hi in scan_points(D_END, 0.025) {
            if !admissible(hi)? {
                return bisect(&admissible, lo, hi).map(Some);
            }
            lo = hi;
        }
        Ok(None)
    }

    /// The end of the range searched for the loss of ellipticity and for bifurcations.
    fn admissible_end(&self) -> f64 {
        self.d_domain_end.map_or(D_END, |d| d * (1.0 - 1e-9))
    }

    fn find_ellipticity_loss(&self) -> Result<Option<f64>> {
        let margin = |d: f64| -> Result<f64> {
            if self.surface.is_some() {
                let (layer, substrate) = self.surface_moduli(d)?;
                return Ok(layer.ellipticity_margin().min(substrate.ellipticity_margin()));
            }
            let (layer, substrate) = self.moduli(d)?;
            Ok(ellipticity_margin(&layer).min(ellipticity_margin(&substrate)))
        };
        let (mut lo, mut margin_lo) = (D_START, margin(D_START)?);
        if margin_lo <= 0.0 {
            return Ok(Some(0.0));
        }
        // The margin is smooth in d: steps double from 1e-3 up to ELLIPTICITY_STEP, and go at
        // most 1.5 times as far as the secant through the last two margins predicts its zero,
        // so that a loss ahead is bracketed in a step or two.
        let end = self.admissible_end();
        let mut step: f64 = 1e-3;
        while lo < end {
            let hi = (lo + step).min(end);
            let margin_hi = margin(hi)?;
            if margin_hi <= 0.0 {
                return brent("loss of ellipticity", margin, lo, hi, D_TOLERANCE).map(Some);
            }
            let slope = (margin_hi - margin_lo) / (hi - lo);
            let to_zero = if slope < 0.0 { -margin_hi / slope } else { f64::INFINITY };
            step = (2.0 * step).min(ELLIPTICITY_STEP).min(1.5 * to_zero).max(1e-4);
            (lo, margin_lo) = (hi, margin_hi);
        }
        Ok(None)
    }

    /// A function of `d` whose sign changes where the bifurcation condition holds at `k`:
    /// the exact determinant, or +-1 from the inertia of the discrete stiffness.
    fn indicator(&self, d: f64, k: f64) -> Result<f64> {
        if let Some(surface) = &self.surface {
            return self.surface_indicator(surface.theta, d, k);
        }
        let (layer, substrate) = self.moduli(d)?;
        match &self.method {
            Method::Exact => {
                // Within a hair of the loss of ellipticity a Stroh root touches the imaginary
                // axis: the search has reached its end without a bifurcation.
                let nearly_lost = |_| Error::NoRoot {
                    what: format!("the bifurcation condition at k = {k} before d = {d} (ellipticity nearly lost)"),
                    lower: 0.0,
                    upper: d,
                };
                let impedance = surface_impedance(&substrate).map_err(nearly_lost)?;
                let layer = LayerSolutions::of(&layer).map_err(nearly_lost)?;
                Ok(bifurcation_determinant(&layer, &impedance, k))
            }
            Method::Discrete(options) => match discrete::negative_eigenvalues(&layer, &substrate, k, options) {
                Some(0) => Ok(1.0),
                _ => Ok(-1.0),
            },
        }
    }

    /// `d_c(k)`: the smallest compression with a bifurcation at wavenumber `k`, found by a scan
    /// from `d = 0` and a bracketed refinement.
    pub fn critical_compression(&self, k: f64) -> Result<f64> {
        self.critical_compression_near(k, None)
    }

    /// `d_c(k)`, starting the bracket search at `hint` (continuation along a curve).
    pub fn critical_compression_near(&self, k: f64, hint: Option<f64>) -> Result<f64> {
        if !(k.is_finite() && k > 0.0) {
            return Err(Error::invalid("k", k, "(0, inf)"));
        }
        let smooth = matches!(self.method, Method::Exact);
        first_sign_change(&|d| self.indicator(d, k), smooth, hint, self.search_end())?.ok_or_else(|| Error::NoRoot {
            what: format!("the bifurcation condition at k = {k} before {}", self.limit_reason()),
            lower: 0.0,
            upper: self.d_limit,
        })
    }

    /// The largest `d` evaluated: just short of the loss of ellipticity, where a Stroh root
    /// reaches the imaginary axis.
    pub(super) fn search_end(&self) -> f64 {
        match self.d_ellipticity_loss {
            Some(d) => d * (1.0 - 1e-6),
            None => self.admissible_end(),
        }
    }

    pub(super) fn limit_reason(&self) -> String {
        match self.d_ellipticity_loss {
            Some(d) if d < 1e-3 => format!(
                "the loss of strong ellipticity at d = {d:.2e}, i.e. at rest (e.g. stiff fibres under compression, or no matrix): no wrinkling answer exists"
            ),
            Some(d) => format!("the loss of ellipticity at d = {d:.6}"),
            None => match self.d_domain_end {
                Some(d) => format!("the end of a law's domain (a Gent law's limiting extensibility) at d = {d:.6}"),
                None => format!("d = {D_END}"),
            },
        }
    }

    /// The onset: `k0` minimising `d_c(k)`, found on a logarithmic grid over `k_range` and
    /// refined by Brent's minimisation. A minimum at an end of the grid is followed beyond it
    /// (down to `K_LONG`, up to `K_SHORT`): it is either an interior minimum there or the
    /// long- or short-wave limit ([`Minimum`]).
    pub fn onset(&self) -> Result<Onset> {
        let (k_lo, k_hi) = self.k_range;
        const GRID: usize = 13;
        let ks: Vec<f64> = (0..GRID)
            .map(|i| k_lo * (k_hi / k_lo).powf(i as f64 / (GRID - 1) as f64))
            .collect();
        let mut curve = Vec::with_capacity(GRID);
        let mut hint = None;
        for &k in &ks {
            // A wavenumber without bifurcation before the search limit counts as d_c = infinity.
            let d = match self.critical_compression_near(k, hint) {
                Err(Error::NoRoot { .. }) => f64::INFINITY,
                other => other?,
            };
            curve.push(d);
            hint = Some(d).filter(|d| d.is_finite());
        }
        let best = (0..GRID)
            .min_by(|&a, &b| curve[a].total_cmp(&curve[b]))
            .expect("non-empty grid");
        if !curve[best].is_finite() {
            return Err(Error::NoRoot {
                what: format!(
                    "wrinkling for k in [{k_lo}, {k_hi}] (or beyond, to {K_LONG} and {K_SHORT}) before {}",
                    self.limit_reason()
                ),
                lower: 0.0,
                upper: self.d_limit,
            });
        }
        let highest = curve.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if highest - curve[best] <= RISE_TOLERANCE {
            return Ok(self.onset_at(f64::NAN, curve[best], Minimum::Flat));
        }
        let (a, b) = match best {
            0 => match self.follow((ks[0], curve[0]), ks[1], K_LONG)? {
                Beyond::Bracket(a, b) => (a, b),
                Beyond::Limit(d_c) => return Ok(self.onset_at(0.0, d_c, Minimum::LongWave)),
            },
            b if b == GRID - 1 => match self.follow((ks[GRID - 1], curve[GRID - 1]), ks[GRID - 2], K_SHORT)? {
                Beyond::Bracket(a, b) => (a, b),
                Beyond::Limit(d_c) => return Ok(self.onset_at(f64::INFINITY, d_c, Minimum::ShortWave)),
            },
            _ => (ks[best - 1], ks[best + 1]),
        };
        let hint = std::cell::Cell::new(curve[best]);
        let (k0, d_c) = brent_minimize(
            |k| {
                let d = self.critical_compression_near(k, Some(hint.get()))?;
                hint.set(d);
                Ok(d)
            },
            a,
            b,
            1e-8,
        )?;
        Ok(self.onset_at(k0, d_c, Minimum::Interior))
    }

    /// Follows a decreasing `d_c(k)` from the grid's end `(k, d)` (whose neighbour inside the
    /// grid is `previous`) towards `end`, by about `PROBES_PER_DECADE` probes per decade: a
    /// bracket of the first rise, or the limit `d_c(end)`.
    fn follow(&self, (mut k, mut d): (f64, f64), mut previous: f64, end: f64) -> Result<Beyond> {
        let factor = (end / k).powf(1.0 / ((end / k).log10().abs() * PROBES_PER_DECADE).ceil().max(1.0));
        while (end - k).abs() > 1e-12 * end {
            let next = if (k * factor - end) * (k - end) <= 0.0 {
                end
            } else {
                k * factor
            };
            let d_next = match self.critical_compression_near(next, Some(d).filter(|d| d.is_finite())) {
                Err(Error::NoRoot { .. }) => f64::INFINITY,
                other => other?,
            };
            if d_next > d + RISE_TOLERANCE {
                let (a, b) = (previous.min(next), previous.max(next));
                return Ok(Beyond::Bracket(a, b));
            }
            if d_next < d {
                (previous, k, d) = (k, next, d_next);
            } else {
                (previous, k) = (k, next);
            }
        }
        Ok(Beyond::Limit(d))
    }

    /// The onset at `(k0, d_c)` of this analysis.
    pub(super) fn onset_at(&self, k0: f64, d_c: f64, minimum: Minimum) -> Onset {
        Onset {
            k0,
            d_c,
            lambda1_c: 1.0 - d_c,
            d_ellipticity_loss: self.d_ellipticity_loss,
            d_domain_end: self.d_domain_end,
            minimum,
        }
    }
}

/// What lies beyond an end of the onset grid.
enum Beyond {
    /// `d_c` rises again between these wavenumbers: an interior minimum.
    Bracket(f64, f64),
    /// `d_c` decreases up to the last probe: its value there.
    Limit(f64),
}

impl StabilityAnalysis {
    /// The onset, continued from a nearby parameter set's onset `previous`: Brent's minimisation
    /// on `k0 (1 +- 15 %)`; falls back to [`Self::onset`] if the minimum is not inside.
    pub fn onset_near(&self, previous: &Onset) -> Result<Onset> {
        if previous.minimum != Minimum::Interior {
            return self.onset();
        }
        let (a, b) = (previous.k0 * 0.85, previous.k0 * 1.15);
        let hint = std::cell::Cell::new(previous.d_c);
        let minimum = brent_minimize(
            |k| {
                let d = self.critical_compression_near(k, Some(hint.get()))?;
                hint.set(d);
                Ok(d)
            },
            a,
            b,
            1e-8,
        );
        // Interior only where d_c rises on both sides by more than the tolerance of a rise (as
        // in `onset`): a nearly flat d_c(k) is classified by the whole search.
        let rises = |k: f64, d_c: f64| -> Result<bool> {
            Ok(self.critical_compression_near(k, Some(d_c))? > d_c + RISE_TOLERANCE)
        };
        match minimum {
            Ok((k0, d_c)) if k0 > a * 1.001 && k0 < b * 0.999 && rises(a, d_c)? && rises(b, d_c)? => {
                Ok(self.onset_at(k0, d_c, Minimum::Interior))
            }
            _ => self.onset(),
        }
    }
}

/// The smallest `d` in `(D_START, end)` at which `indicator` first differs in sign from its
/// value at `D_START` (a bifurcation condition at one wave): bracketed near `hint` or by a scan
/// from rest, then refined by Brent's method if the indicator is continuous (`smooth`) or by
/// bisection of its sign. `None` if the sign never changes before `end`.
pub(super) fn first_sign_change(
    indicator: &dyn Fn(f64) -> Result<f64>,
    smooth: bool,
    hint: Option<f64>,
    end: f64,
) -> Result<Option<f64>> {
    let reference = indicator(D_START)?.signum();
    let stable = |d: f64| -> Result<bool> { Ok(indicator(d)?.signum() == reference) };
    let bracket = match hint.filter(|h| *h > D_START && *h < end) {
        Some(h) => bracket_near(h, end, &stable)?,
        None => bracket_by_scan(end, &stable)?,
    };
    let Some((lo, hi)) = bracket else {
        return Ok(None);
    };
    match smooth {
        true => brent("the bifurcation determinant", indicator, lo, hi, D_TOLERANCE).map(Some),
        false => bisect(&stable, lo, hi).map(Some),
    }
}

fn bracket_by_scan(end: f64, stable: &dyn Fn(f64) -> Result<bool>) -> Result<Option<(f64, f64)>> {
    let mut lo = D_START;
    for hi in scan_points(end, 0.01) {
        if !stable(hi)? {
            return Ok(Some((lo, hi)));
        }
        lo = hi;
    }
    Ok(None)
}

fn bracket_near(hint: f64, end: f64, stable: &dyn Fn(f64) -> Result<bool>) -> Result<Option<(f64, f64)>> {
    let (mut lo, mut hi) = (hint * 0.99, (hint * 1.01).min(end));
    while !stable(lo)? {
        hi = lo;
        lo *= 0.8;
        if lo < 1e-4 {
            return bracket_by_scan(end, stable);
        }
    }
    while stable(hi)? {
        if hi >= end {
            return Ok(None);
        }
        lo = hi;
        hi = (hi * 1.1).min(end);
    }
    Ok(Some((lo, hi)))
}

/// Scan points from `D_START` to `end`: geometric at small `d`, steps of `max_step` beyond.
fn scan_points(end: f64, max_step: f64) -> impl Iterator<Item = f64> {
    let mut d = D_START;
    std::iter::from_fn(move || {
        if d >= end {
            return None;
        }
        d = (d * 1.25).max(1e-4).min(d + max_step).min(end);
        Some(d)
    })
}

fn bisect(stable: &dyn Fn(f64) -> Result<bool>, mut lo: f64, mut hi: f64) -> Result<f64> {
    while hi - lo > D_TOLERANCE.max(1e-15 * hi) {
        let mid = 0.5 * (lo + hi);
        if stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}
