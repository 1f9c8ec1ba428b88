//! Allocation-free bracketing root finder for the one-parameter profile equations.
//!
//! Every profile family is reduced (by eliminating the other unknowns with the acceleration,
//! velocity and duration equations) to one smooth residual `f(x)` of one parameter on an interval.
//! [`scan`] samples the interval, brackets every sign change, and additionally looks for pairs of
//! close roots hidden between samples of equal sign (a local minimum of `|f|` is followed by a
//! golden-section search of the extremum of `f`; if the extremum has the opposite sign both roots
//! are bracketed). Brackets are refined by the Illinois variant of regula falsi with a bisection
//! safeguard, to full double precision.

/// Fixed-capacity list of roots.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Roots {
    n: usize,
    x: [f64; Self::CAP],
}

impl Roots {
    const CAP: usize = 24;

    pub fn new() -> Self {
        Self {
            n: 0,
            x: [0.0; Self::CAP],
        }
    }

    pub fn push(&mut self, x: f64) {
        if self.n < Self::CAP {
            // Skip duplicates found from adjacent brackets.
            for &y in &self.x[..self.n] {
                if (y - x).abs() <= 1e-15 * (1.0 + x.abs()) {
                    return;
                }
            }
            self.x[self.n] = x;
            self.n += 1;
        }
    }

    pub fn as_slice(&self) -> &[f64] {
        &self.x[..self.n]
    }
}

/// Refines a bracket `[a, b]` with `f(a)·f(b) < 0`.
fn refine<F: FnMut(f64) -> f64>(
    f: &mut F,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
) -> f64 {
    let mut side = 0i8;
    for it in 0..120 {
        if fa == 0.0 {
            return a;
        }
        if fb == 0.0 {
            return b;
        }
        let width = (b - a).abs();
        if width <= 2.0 * f64::EPSILON * a.abs().max(b.abs()) || width == 0.0 {
            break;
        }
        // Regula falsi step, every fourth step (or if degenerate) a bisection.
        let mut c = (a * fb - b * fa) / (fb - fa);
        if it % 4 == 3 || !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if !fc.is_finite() {
            // Should not happen inside a bracket of finite values; fall back to bisection.
            return 0.5 * (a + b);
        }
        if (fc > 0.0) == (fb > 0.0) {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    if fa.abs() < fb.abs() { a } else { b }
}

/// Golden-section search for the extremum of `f` on `[a, b]` in the direction that brings `f`
/// towards zero (`sign` is the sign of `f` at the samples). Returns `(x, f(x))`.
fn extremum<F: FnMut(f64) -> f64>(f: &mut F, mut a: f64, mut b: f64, sign: f64) -> (f64, f64) {
    const G: f64 = 0.618_033_988_749_894_8;
    let mut c = b - G * (b - a);
    let mut d = a + G * (b - a);
    let mut fc = sign * f(c);
    let mut fd = sign * f(d);
    for _ in 0..40 {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - G * (b - a);
            fc = sign * f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + G * (b - a);
            fd = sign * f(d);
        }
        if fc.min(fd) < 0.0 {
            break;
        }
    }
    if fc < fd {
        (c, sign * fc)
    } else {
        (d, sign * fd)
    }
}

/// Finds the roots of `f` on `[lo, hi]` using `samples + 1` equally spaced samples. Non-finite
/// samples mark points where the family is undefined and are never bracketed across.
pub(crate) fn scan<F: FnMut(f64) -> f64>(
    f: &mut F,
    lo: f64,
    hi: f64,
    samples: usize,
    out: &mut Roots,
) {
    if !lo.is_finite() || !hi.is_finite() || lo > hi {
        return;
    }
    if lo == hi {
        let v = f(lo);
        if v == 0.0 {
            out.push(lo);
        }
        return;
    }
    let n = samples.max(2);
    let h = (hi - lo) / n as f64;
    let x_at = |i: usize| if i == n { hi } else { lo + h * i as f64 };
    let mut x_prev2 = f64::NAN;
    let mut f_prev2 = f64::NAN;
    let mut x_prev = lo;
    let mut f_prev = f(lo);
    if f_prev == 0.0 {
        out.push(lo);
    }
    for i in 1..=n {
        let x = x_at(i);
        let fx = f(x);
        if fx == 0.0 {
            out.push(x);
        } else if fx.is_finite() && f_prev.is_finite() && f_prev != 0.0 {
            if (fx > 0.0) != (f_prev > 0.0) {
                out.push(refine(f, x_prev, f_prev, x, fx));
            } else if f_prev2.is_finite()
                && f_prev2 != 0.0
                && (f_prev2 > 0.0) == (f_prev > 0.0)
                && f_prev.abs() < f_prev2.abs()
                && f_prev.abs() < fx.abs()
            {
                // |f| has a local minimum near x_prev: look for a hidden pair of roots.
                let sign = f_prev.signum();
                let (xm, fm) = extremum(f, x_prev2, x, sign);
                if fm == 0.0 {
                    out.push(xm);
                } else if fm.is_finite() && (fm > 0.0) != (sign > 0.0) {
                    out.push(refine(f, x_prev2, f_prev2, xm, fm));
                    out.push(refine(f, xm, fm, x, fx));
                }
            }
        }
        x_prev2 = x_prev;
        f_prev2 = f_prev;
        x_prev = x;
        f_prev = fx;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_simple_and_close_roots() {
        let mut r = Roots::new();
        let mut f = |x: f64| (x - 0.3) * (x - 0.7) * (x + 2.0);
        scan(&mut f, -3.0, 3.0, 8, &mut r);
        let mut v: Vec<f64> = r.as_slice().to_vec();
        v.sort_by(f64::total_cmp);
        assert_eq!(v.len(), 3);
        assert!(
            (v[0] + 2.0).abs() < 1e-14 && (v[1] - 0.3).abs() < 1e-14 && (v[2] - 0.7).abs() < 1e-14
        );

        // Two roots 1e-3 apart between equal-sign samples.
        let mut r = Roots::new();
        let mut g = |x: f64| (x - 0.6) * (x - 0.601);
        scan(&mut g, -1.0, 2.0, 4, &mut r);
        assert_eq!(r.as_slice().len(), 2);
    }
}
