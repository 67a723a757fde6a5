//! Brent's minimisation of a scalar function on an interval (golden section safeguarding
//! parabolic interpolation).

use crate::error::Result;

/// Minimises `f` on `[a, b]` to absolute tolerance `tol` in x; returns `(x_min, f(x_min))`.
pub fn brent_minimize<F>(mut f: F, a: f64, b: f64, tol: f64) -> Result<(f64, f64)>
where
    F: FnMut(f64) -> Result<f64>,
{
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (a.min(b), a.max(b));
    let mut x = a + GOLDEN * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let middle = 0.5 * (a + b);
        let tol1 = tol + 1e-12 * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - middle).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(middle - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x < middle { b - x } else { a - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol1 { x + d } else { x + tol1.copysign(d) };
        let fu = f(u)?;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    Ok((x, fx))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_minimum_of_smooth_function() {
        let (x, fx) = brent_minimize(
            |x: f64| Ok((x - 0.7).powi(2) + 0.3 + (x - 0.7).powi(4)),
            0.0,
            2.0,
            1e-10,
        )
        .unwrap();
        assert!((x - 0.7).abs() < 1e-8 && (fx - 0.3).abs() < 1e-15);
        let (x, _) = brent_minimize(|x: f64| Ok(-x.sin()), 0.0, 3.0, 1e-10).unwrap();
        assert!((x - std::f64::consts::FRAC_PI_2).abs() < 1e-8);
    }
}
