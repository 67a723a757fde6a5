//! Tick marks at round values: 1, 2 or 5 times a power of ten on a linear axis, the same values
//! on a logarithmic one, and round degrees on an axis of angles held in radians. Labels are
//! the shortest that tell the ticks apart ("0.2", not "0.200").

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use std::ops::Range;

/// How an axis holds and shows its values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AxisScale {
    /// Values plotted as they are.
    #[default]
    Linear,
    /// Values plotted as their `log10`, labelled as the values.
    Log10,
    /// Angles plotted in radians, labelled in degrees.
    Degrees,
}

/// About this many ticks on an axis.
const TICKS: f64 = 5.0;

/// The round step nearest `span / TICKS` among 1, 2, 5 times a power of ten.
fn round_step(span: f64) -> f64 {
    let raw = span / TICKS;
    let power = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .min_by(|a, b| (a / raw).ln().abs().total_cmp(&(b / raw).ln().abs()))
        .expect("four candidates")
}

/// The multiples of `step` in `[lo, hi]`.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// Ticks (in plotted coordinates) at round values of an axis spanning `[lo, hi]` (plotted).
pub fn round_ticks(lo: f64, hi: f64, scale: AxisScale) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return vec![lo];
    }
    match scale {
        AxisScale::Linear => multiples(lo, hi, round_step(hi - lo)),
        AxisScale::Degrees => {
            let (a, b) = (lo.to_degrees(), hi.to_degrees());
            let raw = (b - a) / TICKS;
            let step = [1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0]
                .into_iter()
                .min_by(|x, y| (x / raw).ln().abs().total_cmp(&(y / raw).ln().abs()))
                .expect("candidates");
            multiples(a, b, step).into_iter().map(f64::to_radians).collect()
        }
        AxisScale::Log10 => {
            let decades = (lo.floor() as i64)..=(hi.ceil() as i64);
            let mantissas: &[f64] = if hi - lo > 2.5 { &[1.0] } else { &[1.0, 2.0, 5.0] };
            let ticks: Vec<f64> = decades
                .flat_map(|n| mantissas.iter().map(move |m| (m * 10f64.powi(n as i32)).log10()))
                .filter(|v| *v >= lo - 1e-9 && *v <= hi + 1e-9)
                .collect();
            match ticks.len() >= 2 {
                true => ticks,
                // Less than a decade with one round value: round values of the values themselves.
                false => {
                    let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
                    multiples(a, b, round_step(b - a))
                        .into_iter()
                        .filter(|v| *v > 0.0)
                        .map(f64::log10)
                        .collect()
                }
            }
        }
    }
}

/// A plotted axis `[lo, hi]` whose ticks are [`round_ticks`] (for a chart's
/// `build_cartesian_2d`; its labels come from [`tick_label`] through the mesh's formatter).
pub struct RoundTicks {
    axis: RangedCoordf64,
    ticks: Vec<f64>,
}

impl RoundTicks {
    pub fn new(lo: f64, hi: f64, scale: AxisScale) -> Self {
        RoundTicks {
            axis: (lo..hi).into(),
            ticks: round_ticks(lo, hi, scale),
        }
    }
}

impl Ranged for RoundTicks {
    type ValueType = f64;
    type FormatOption = NoDefaultFormatting;

    fn range(&self) -> Range<f64> {
        self.axis.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.axis.map(value, limit)
    }

    /// The round ticks, and no light mesh lines between them.
    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        match hint.weight().allow_light_points() {
            true => Vec::new(),
            false => self.ticks.clone(),
        }
    }
}

impl ValueFormatter<f64> for RoundTicks {
    fn format(value: &f64) -> String {
        shortest(*value)
    }
}

/// The label of the tick at plotted coordinate `v`.
pub fn tick_label(v: f64, scale: AxisScale) -> String {
    let value = match scale {
        AxisScale::Linear => v,
        AxisScale::Log10 => 10f64.powf(v),
        AxisScale::Degrees => v.to_degrees(),
    };
    shortest(value)
}

/// `value` rounded to six significant digits, written without trailing zeros (and without a
/// negative zero).
fn shortest(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return if value.is_finite() {
            "0".into()
        } else {
            value.to_string()
        };
    }
    let digits = 5 - value.abs().log10().floor() as i32;
    let rounded = match digits >= 0 {
        true => {
            let scale = 10f64.powi(digits);
            (value * scale).round() / scale
        }
        false => {
            let scale = 10f64.powi(-digits);
            (value / scale).round() * scale
        }
    };
    let text = format!("{rounded}");
    if text == "-0" {
        "0".into()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(lo: f64, hi: f64, scale: AxisScale) -> Vec<String> {
        round_ticks(lo, hi, scale)
            .into_iter()
            .map(|v| tick_label(v, scale))
            .collect()
    }

    #[test]
    fn ticks_fall_on_round_values() {
        assert_eq!(
            labels(0.0, 0.5, AxisScale::Linear),
            ["0", "0.1", "0.2", "0.3", "0.4", "0.5"]
        );
        assert_eq!(
            labels(-0.03, 0.21, AxisScale::Linear),
            ["0", "0.05", "0.1", "0.15", "0.2"]
        );
        assert_eq!(
            labels(0.0, std::f64::consts::FRAC_PI_2, AxisScale::Degrees),
            ["0", "15", "30", "45", "60", "75", "90"]
        );
        let log = |a: f64, b: f64| labels(a.log10(), b.log10(), AxisScale::Log10);
        assert_eq!(log(1.2, 100.0), ["2", "5", "10", "20", "50", "100"]);
        assert_eq!(
            log(1e-2, 1e6),
            ["0.01", "0.1", "1", "10", "100", "1000", "10000", "100000", "1000000"]
        );
        // Within one round value: the values' own round steps.
        assert_eq!(log(3.0, 4.5), ["3", "3.2", "3.4", "3.6", "3.8", "4", "4.2", "4.4"]);
    }

    #[test]
    fn labels_are_the_shortest_and_never_negative_zero() {
        assert_eq!(shortest(0.30000000000000004), "0.3");
        assert_eq!(shortest(-1e-17), "-0.00000000000000001");
        assert_eq!(shortest(-0.0), "0");
        assert_eq!(shortest(2.5e6), "2500000");
        assert_eq!(shortest(1.0 / 3.0), "0.333333");
    }
}
