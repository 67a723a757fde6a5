//! Bracketed scalar root finding (Brent's method) and bracket search.

use crate::error::{Error, Result};

/// Finds a root of `f` in `[a, b]`, where `f(a)` and `f(b)` differ in sign, to absolute
/// tolerance `tol` in x, by Brent's method (inverse quadratic interpolation safeguarded by
/// bisection). `what` names the equation in the error message.
pub fn brent<F>(what: &str, mut f: F, a: f64, b: f64, tol: f64) -> Result<f64>
where
    F: FnMut(f64) -> Result<f64>,
{
    let (fa, fb) = (f(a)?, f(b)?);
    brent_from(what, f, (a, fa), (b, fb), tol)
}

/// [`brent`] from a bracket whose values `f(a)`, `f(b)` are known (e.g. from a scan).
pub fn brent_from<F>(what: &str, mut f: F, (a, fa): (f64, f64), (b, fb): (f64, f64), tol: f64) -> Result<f64>
where
    F: FnMut(f64) -> Result<f64>,
{
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (fa, fb);
    if !(fa.is_finite() && fb.is_finite()) {
        return Err(Error::NonFinite(what.to_string()));
    }
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() {
        return Err(Error::NoRoot {
            what: what.to_string(),
            lower: a.min(b),
            upper: a.max(b),
        });
    }
    let (mut c, mut fc) = (a, fa);
    let mut step = b - a;
    let mut previous_step = step;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            step = b - a;
            previous_step = step;
        }
        if fc.abs() < fb.abs() {
            (a, b, c) = (b, c, b);
            (fa, fb, fc) = (fb, fc, fb);
        }
        let tolerance = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let midpoint = 0.5 * (c - b);
        if midpoint.abs() <= tolerance || fb == 0.0 {
            return Ok(b);
        }
        if previous_step.abs() >= tolerance && fa.abs() > fb.abs() {
            // Interpolation: secant if only two points, inverse quadratic otherwise.
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * midpoint * s;
                q = 1.0 - s;
            } else {
                let qa = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * midpoint * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * midpoint * q - (tolerance * q).abs()).min((previous_step * q).abs()) {
                previous_step = step;
                step = p / q;
            } else {
                step = midpoint;
                previous_step = step;
            }
        } else {
            step = midpoint;
            previous_step = step;
        }
        a = b;
        fa = fb;
        b += if step.abs() > tolerance {
            step
        } else {
            tolerance.copysign(midpoint)
        };
        fb = f(b)?;
        if !fb.is_finite() {
            return Err(Error::NonFinite(what.to_string()));
        }
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_known_roots() {
        let r = brent("x^3 - 2", |x| Ok(x * x * x - 2.0), 0.0, 2.0, 1e-14).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-13);
        let r = brent("cos", |x: f64| Ok(x.cos()), 0.0, 3.0, 1e-14).unwrap();
        assert!((r - std::f64::consts::FRAC_PI_2).abs() < 1e-13);
    }

    #[test]
    fn brent_reports_missing_bracket() {
        let e = brent("x^2 + 1", |x| Ok(x * x + 1.0), -1.0, 1.0, 1e-12).unwrap_err();
        assert!(e.to_string().contains("x^2 + 1"));
    }
}
