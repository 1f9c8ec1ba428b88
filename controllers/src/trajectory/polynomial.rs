//! Low-degree polynomials on an interval: exact interpolation and all real roots.
//!
//! Inside one smooth window of a profile family the residual equations are polynomials in a
//! suitable parameter (see [`super::peak_window`]), of degree at most [`MAX_DEGREE`]. Their
//! coefficients are closed forms ([`closed_form_roots`], from [`super::peak_polynomials`]) or,
//! as a fallback, *interpolated* from `n + 1` evaluations of the residual at Chebyshev points
//! of the window ([`polynomial_roots`]); either is checked against the residual at one more
//! point. The real roots are isolated by the critical points (the roots of the derivative,
//! recursively down to a closed-form quadratic) and refined by safeguarded Halley steps. Every
//! step is closed form or a bracketed iteration on a polynomial: no sampling of the residual.
//!
//! The interpolation variable is the window mapped to `t ∈ [−1, 1]`, where the monomial basis
//! of degree ≤ 6 is well conditioned.
//!
//! Most windows hold no root. Before any critical point is computed, the polynomial (and, on
//! the way down, each derivative) is tested in the Bernstein basis of `[−1, 1]`: a polynomial
//! lies in the convex hull of its Bernstein coefficients, so if they all have the same sign,
//! clear of zero by more than the tangency threshold and the rounding of the conversion, the
//! polynomial has no root and no tangency there, and the isolation below would report none
//! (see [`bernstein_excludes`]). The derivative's Bernstein coefficients are scaled differences
//! of the polynomial's, so the test costs `O(n)` per level after one `O(n²)` conversion.

use super::roots::Roots;

/// Highest supported degree.
pub(crate) const MAX_DEGREE: usize = 6;

/// A polynomial `Σ c_k t^k` in the normalised variable `t ∈ [−1, 1]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Poly {
    /// Degree (number of coefficients − 1).
    pub n: usize,
    /// Coefficients, lowest first.
    pub c: [f64; MAX_DEGREE + 1],
}

impl Poly {
    /// Value at `t` (Horner).
    #[inline]
    pub fn eval(&self, t: f64) -> f64 {
        let mut y = self.c[self.n];
        for k in (0..self.n).rev() {
            y = y * t + self.c[k];
        }
        y
    }

    /// Value and first derivative at `t`.
    #[inline]
    pub fn eval_d(&self, t: f64) -> (f64, f64) {
        let mut y = self.c[self.n];
        let mut dy = 0.0;
        for k in (0..self.n).rev() {
            dy = dy * t + y;
            y = y * t + self.c[k];
        }
        (y, dy)
    }

    /// Value, first and second derivative at `t`.
    #[inline]
    pub fn eval_d2(&self, t: f64) -> (f64, f64, f64) {
        let mut y = self.c[self.n];
        let mut dy = 0.0;
        let mut d2y = 0.0;
        for k in (0..self.n).rev() {
            d2y = d2y * t + dy;
            dy = dy * t + y;
            y = y * t + self.c[k];
        }
        (y, dy, 2.0 * d2y)
    }

    fn derivative(&self) -> Self {
        let mut d = Self {
            n: self.n.saturating_sub(1),
            c: [0.0; MAX_DEGREE + 1],
        };
        for k in 1..=self.n {
            d.c[k - 1] = k as f64 * self.c[k];
        }
        d
    }

    /// Largest coefficient magnitude (the scale of the values on `[−1, 1]`).
    pub fn scale(&self) -> f64 {
        self.c[..=self.n].iter().fold(0.0, |m, x| m.max(x.abs()))
    }
}

/// `BERNSTEIN[n][i][k]`: the `i`-th Bernstein coefficient of `t^k` in degree `n` on
/// `t ∈ [−1, 1]` (with `t = 2s − 1`, basis `C(n, i) s^i (1 − s)^(n−i)`), i.e.
/// `Σ_j C(k, j) C(n − k, i − j) (−1)^(k−j) / C(n, i)`. Every entry has magnitude ≤ 1 (the
/// Bernstein coefficients of `t^k` are averages of `±1` products), so the conversion is
/// well conditioned.
const BERNSTEIN: [[[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1]; MAX_DEGREE + 1] = bernstein_table();

const fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let mut r = 1.0;
    let mut i = 0;
    while i < k {
        r = r * (n - i) as f64 / (i + 1) as f64;
        i += 1;
    }
    r
}

const fn bernstein_table() -> [[[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1]; MAX_DEGREE + 1] {
    let mut m = [[[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    let mut n = 0;
    while n <= MAX_DEGREE {
        let mut i = 0;
        while i <= n {
            let mut k = 0;
            while k <= n {
                let mut sum = 0.0;
                let mut j = 0;
                while j <= k {
                    if j <= i && i - j <= n - k {
                        let sign = if (k - j) % 2 == 0 { 1.0 } else { -1.0 };
                        sum += sign * binomial(k, j) * binomial(n - k, i - j);
                    }
                    j += 1;
                }
                m[n][i][k] = sum / binomial(n, i);
                k += 1;
            }
            i += 1;
        }
        n += 1;
    }
    m
}

/// Bernstein coefficients of `p` on `[−1, 1]` (see [`BERNSTEIN`]).
fn bernstein(p: &Poly) -> [f64; MAX_DEGREE + 1] {
    match p.n {
        0 => bernstein_n::<0>(&p.c),
        1 => bernstein_n::<1>(&p.c),
        2 => bernstein_n::<2>(&p.c),
        3 => bernstein_n::<3>(&p.c),
        4 => bernstein_n::<4>(&p.c),
        5 => bernstein_n::<5>(&p.c),
        _ => bernstein_n::<6>(&p.c),
    }
}

/// [`bernstein`] for the degree `N` (fixed, so that the loops unroll).
#[inline(always)]
fn bernstein_n<const N: usize>(c: &[f64; MAX_DEGREE + 1]) -> [f64; MAX_DEGREE + 1] {
    let m = &BERNSTEIN[N];
    let mut b = [0.0; MAX_DEGREE + 1];
    for i in 0..=N {
        let mut s = 0.0;
        for k in 0..=N {
            s += m[i][k] * c[k];
        }
        b[i] = s;
    }
    b
}

/// Bernstein coefficients of `p′` (in `t`) from those of `p` (degree `n`):
/// `(n/2)(b_{i+1} − b_i)`.
fn bernstein_derivative(b: &[f64; MAX_DEGREE + 1], n: usize) -> [f64; MAX_DEGREE + 1] {
    let mut d = [0.0; MAX_DEGREE + 1];
    let h = 0.5 * n as f64;
    for i in 0..n {
        d[i] = h * (b[i + 1] - b[i]);
    }
    d
}

/// Whether the Bernstein coefficients `b[..=n]` prove that the polynomial has neither a root nor
/// a reported tangency on `[−1, 1]`: all of one sign and clear of zero by `margin`. The
/// polynomial is bounded below by the smallest coefficient (convex hull property), so with
/// `margin` above the tangency threshold plus the rounding of the coefficients and of the
/// evaluations, [`roots_rec`] would report nothing either.
#[inline]
fn bernstein_excludes(b: &[f64; MAX_DEGREE + 1], n: usize, margin: f64) -> bool {
    let (mut lo, mut hi) = (b[0], b[0]);
    for &x in &b[1..=n] {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    lo > margin || hi < -margin
}

/// Chebyshev points `cos((2k + 1)π / (2m))`, `k = 0..m`, for `m = n + 1` nodes, per degree `n`.
#[allow(clippy::excessive_precision, clippy::approx_constant)]
const CHEBYSHEV: [[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1] = [
    [6.123233995736766e-17, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        0.7071067811865476,
        -0.7071067811865475,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.8660254037844387,
        6.123233995736766e-17,
        -0.8660254037844387,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.9238795325112867,
        0.38268343236508984,
        -0.3826834323650897,
        -0.9238795325112867,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.9510565162951535,
        0.5877852522924731,
        6.123233995736766e-17,
        -0.587785252292473,
        -0.9510565162951535,
        0.0,
        0.0,
    ],
    [
        0.9659258262890683,
        0.7071067811865476,
        0.25881904510252074,
        -0.25881904510252063,
        -0.7071067811865475,
        -0.9659258262890682,
        0.0,
    ],
    [
        0.9749279121818236,
        0.7818314824680298,
        0.4338837391175582,
        6.123233995736766e-17,
        -0.43388373911755806,
        -0.7818314824680295,
        -0.9749279121818237,
    ],
];

/// The interpolating polynomial of degree `n` through `(t_k, y_k)`, `k = 0..=n`
/// (Newton divided differences, expanded to monomials).
pub(crate) fn interpolate(n: usize, t: &[f64; MAX_DEGREE + 1], y: &[f64; MAX_DEGREE + 1]) -> Poly {
    let mut dd = *y;
    for level in 1..=n {
        for k in (level..=n).rev() {
            dd[k] = (dd[k] - dd[k - 1]) / (t[k] - t[k - level]);
        }
    }
    // p(t) = dd0 + (t − t0)(dd1 + (t − t1)(dd2 + …)): expand from the innermost term.
    let mut c = [0.0; MAX_DEGREE + 1];
    c[0] = dd[n];
    let mut deg = 0;
    for k in (0..n).rev() {
        // c ← c·(t − t_k) + dd_k
        deg += 1;
        for i in (1..=deg).rev() {
            c[i] = c[i - 1] - t[k] * c[i];
        }
        c[0] = -t[k] * c[0] + dd[k];
    }
    Poly { n, c }
}

/// Real roots of `p` in `[lo, hi] ⊆ [−1, 1]`, unsorted, written to `out`; returns their number.
/// Double roots (tangencies) are reported at the critical point when `|p|` there is below
/// `1e-12 · scale`.
pub(crate) fn real_roots(p: &Poly, lo: f64, hi: f64, out: &mut [f64; MAX_DEGREE]) -> usize {
    // Strip vanishing leading coefficients.
    let mut q = *p;
    let s = q.scale();
    if s == 0.0 {
        return 0;
    }
    while q.n > 0 && q.c[q.n].abs() <= 1e-14 * s {
        q.n -= 1;
    }
    roots_rec(&q, lo, hi, s, 0.0, None, 0, out)
}

/// `depth` 0 is the polynomial itself (roots to full precision); deeper levels are derivatives,
/// whose roots only separate monotone pieces and are refined to a relative 1e-10.
///
/// `bern`: the Bernstein coefficients of `p` on `[lo, hi] = [−1, 1]` at depth > 0 (computed
/// here at depth 0, and `None` on any other interval); `rounding` bounds their rounding error
/// (and that of evaluating `p`) at depth 0, set here at depth 0.
#[allow(clippy::too_many_arguments)]
fn roots_rec(
    p: &Poly,
    lo: f64,
    hi: f64,
    scale: f64,
    rounding: f64,
    bern: Option<&[f64; MAX_DEGREE + 1]>,
    depth: usize,
    out: &mut [f64; MAX_DEGREE],
) -> usize {
    // On [−1, 1], |p(t) − c0| ≤ Σ_{k≥1} |c_k|: no root (nor tangency) if c0 dominates.
    let tail: f64 = p.c[1..=p.n].iter().map(|c| c.abs()).sum();
    if p.c[0].abs() > tail * (1.0 + 1e-12) + 1e-12 * scale {
        return 0;
    }
    // Convex hull of the Bernstein coefficients: no root nor tangency (module documentation).
    // The margin covers the tangency threshold `1e-12 · scale` used below and the rounding.
    let b0;
    let (bern, rounding) = if depth == 0 && p.n >= 2 && lo == -1.0 && hi == 1.0 {
        // Rounding of the conversion (entries of magnitude ≤ 1, at most 7 terms: below
        // 16 ε Σ|c_k| ≈ 3.6e-15 Σ|c_k|) and of evaluating p, with a factor of 100 to spare;
        // each derivative level multiplies it by at most n ≤ 6.
        b0 = bernstein(p);
        (Some(&b0), 1e-12 * (tail + p.c[0].abs()))
    } else {
        (bern, rounding)
    };
    let depth_rounding = rounding * 6f64.powi(depth as i32);
    if let Some(b) = bern
        && p.n >= 2
        && bernstein_excludes(b, p.n, 1e-12 * scale + depth_rounding)
    {
        return 0;
    }
    let mut n_out = 0;
    let mut push = |x: f64, out: &mut [f64; MAX_DEGREE]| {
        if n_out < MAX_DEGREE && x >= lo && x <= hi {
            out[n_out] = x;
            n_out += 1;
        }
    };
    match p.n {
        0 => return 0,
        1 => {
            if p.c[1] != 0.0 {
                push(-p.c[0] / p.c[1], out);
            }
            return n_out;
        }
        2 => {
            let (a, b, c) = (p.c[2], p.c[1], p.c[0]);
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                if q != 0.0 {
                    push(q / a, out);
                    push(c / q, out);
                } else {
                    push(0.0, out);
                }
            } else if disc > -1e-13 * (b * b).max((4.0 * a * c).abs()) {
                // Numerically a double root.
                push(-b / (2.0 * a), out);
            }
            return n_out;
        }
        _ => {}
    }
    // Critical points split [lo, hi] into intervals where p is monotone.
    let d = p.derivative();
    let mut crit = [0.0; MAX_DEGREE];
    let db = bern.map(|b| bernstein_derivative(b, p.n));
    let nc = roots_rec(
        &d,
        lo,
        hi,
        scale,
        rounding,
        db.as_ref(),
        depth + 1,
        &mut crit,
    );
    let tol = if depth == 0 {
        4.0 * f64::EPSILON
    } else {
        1e-10
    };
    let crit = &mut crit[..nc];
    crit.sort_unstable_by(f64::total_cmp);
    let mut a = lo;
    let mut fa = p.eval(a);
    if fa == 0.0 {
        push(a, out);
    }
    for k in 0..=nc {
        let b = crit.get(k).copied().unwrap_or(hi);
        let fb = p.eval(b);
        if b > a {
            if fb == 0.0 {
                push(b, out);
            } else if fa != 0.0 && (fa > 0.0) != (fb > 0.0) {
                push(monotone_root(p, a, fa, b, fb, tol), out);
            } else if k < nc && fb.abs() <= 1e-12 * scale {
                // Tangency at a critical point.
                push(b, out);
            }
        }
        a = b;
        fa = fb;
    }
    n_out
}

/// The single root of a monotone `p` on `[a, b]` with a sign change: Halley steps
/// `x − 2pp′/(2p′² − pp″)` from the secant point, kept inside the shrinking bracket (bisection
/// when a step leaves it), until the step is below `tol` (relative). Halley's iteration
/// converges cubically; `p″` costs a third Horner chain that runs alongside the other two, and
/// on the benchmark's cases it needs 5.8 (roots) and 5.0 (critical points) evaluations per root
/// on average instead of Newton's 7.8 and 6.9 (5000 cases per DoF count).
fn monotone_root(p: &Poly, mut a: f64, mut fa: f64, mut b: f64, fb: f64, tol: f64) -> f64 {
    let mut x = (a * fb - b * fa) / (fb - fa);
    if !(x > a.min(b) && x < a.max(b)) {
        x = 0.5 * (a + b);
    }
    for _ in 0..100 {
        let (f, df, d2f) = p.eval_d2(x);
        if f == 0.0 {
            return x;
        }
        if (f > 0.0) == (fa > 0.0) {
            a = x;
            fa = f;
        } else {
            b = x;
        }
        let mut nx = x - 2.0 * f * df / (2.0 * df * df - f * d2f);
        // Converged: test the step before the bracket safeguard. Once x sits on the
        // root, x is also a bracket end, and a tiny step beyond it must not trigger the
        // bisection fallback (which restarted from the midpoint of a wide bracket and cost
        // dozens of iterations).
        if (nx - x).abs() <= tol * (1.0 + x.abs()) {
            return if nx > a.min(b) && nx < a.max(b) {
                nx
            } else {
                x
            };
        }
        if !(nx > a.min(b) && nx < a.max(b)) {
            nx = 0.5 * (a + b);
        }
        if (nx - x).abs() <= tol * (1.0 + x.abs()) || (b - a).abs() <= 1e-15 {
            return nx;
        }
        x = nx;
    }
    x
}

/// Roots of the polynomial `Σ c_k w^k` of degree `n` (coefficients in the raw variable `w`,
/// e.g. from the closed forms of [`super::peak_polynomials`]) on `[wl, wr]`, polished by Newton
/// steps on the residual `f` they stand for, pushed to `out`. Returns `false` (leaving `out`
/// unchanged) if a polished root still leaves a residual that the polynomial does not explain
/// (the caller then interpolates or samples).
pub(crate) fn closed_form_roots<F: FnMut(f64) -> f64>(
    n: usize,
    c: &[f64; MAX_DEGREE + 1],
    f: &mut F,
    wl: f64,
    wr: f64,
    out: &mut Roots,
) -> bool {
    closed_form_roots_checked(n, c, f, wl, wr, None, RootSet::All, out)
}

/// Which roots of a window a caller needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RootSet {
    /// Every root (extremal profiles: each one may end a blocked interval).
    All,
    /// Any one root, if the polynomial changes sign over the window; otherwise every root.
    /// For callers to which any verified profile will do (fixed-duration profiles): the root
    /// is bracketed by the window's end points and found without isolating the others, and
    /// it is a root of the polynomial, not polished on the residual. A caller whose single
    /// root does not give a valid profile asks again with [`Self::All`].
    AnyOne,
    /// The caller has proved that the residual has exactly one root in the window and
    /// changes sign between its ends (a monotone residual): if the polynomial changes sign
    /// over the window too, that root is bracketed by the window's end points and refined
    /// without isolating critical points, then polished on the residual like every root of
    /// [`Self::All`]; otherwise every root, as [`Self::All`].
    Single,
}

/// [`closed_form_roots`] with the guard value supplied by the caller: `check = (w, f(w))` for
/// some `w` inside `[wl, wr]` that the caller has already evaluated (saves one evaluation of
/// the residual per window), and the roots needed (`set`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn closed_form_roots_checked<F: FnMut(f64) -> f64>(
    n: usize,
    c: &[f64; MAX_DEGREE + 1],
    f: &mut F,
    wl: f64,
    wr: f64,
    check: Option<(f64, f64)>,
    set: RootSet,
    out: &mut Roots,
) -> bool {
    if !(wl.is_finite() && wr.is_finite() && wr >= wl) || n > MAX_DEGREE {
        return false;
    }
    if c[..=n].iter().any(|x| !x.is_finite()) {
        return false;
    }
    let mid = 0.5 * (wl + wr);
    let half = 0.5 * (wr - wl);
    // q(t) = p(mid + half·t): Taylor shift by `mid`, then scale.
    let mut q = Poly { n, c: *c };
    for k in 0..n {
        for i in (k..n).rev() {
            q.c[i] += mid * q.c[i + 1];
        }
    }
    let mut h = 1.0;
    for k in 0..=n {
        q.c[k] *= h;
        h *= half;
    }
    if half == 0.0 {
        q.n = 0;
    }
    let scale = q.scale();
    let w_of = |t: f64| (mid + half * t).clamp(wl, wr);
    // One evaluation of the residual itself guards against a closed form that does not describe
    // it (a window whose shape differs from the expected one): the roots of a wrong polynomial
    // would silently miss profiles.
    const T_CHECK: f64 = 0.412_345;
    let (tc, yc) = match check {
        Some((w, y)) if w >= wl && w <= wr => (if half > 0.0 { (w - mid) / half } else { 0.0 }, y),
        _ => (T_CHECK, f(w_of(T_CHECK))),
    };
    if !yc.is_finite() || (yc - q.eval(tc)).abs() > 1e-9 * (scale + yc.abs()) + 1e-300 {
        return false;
    }
    // Newton polish of a root `tr` of q on f itself (with q's slope); `None` if f does not
    // vanish there to a relative 1e-8 (the closed form does not describe f).
    let mut polish = |tr: f64| -> Option<f64> {
        let mut tt = tr;
        let mut ft = f(w_of(tt));
        for _ in 0..3 {
            if !ft.is_finite() {
                return None;
            }
            if ft.abs() <= 1e-14 * scale {
                break;
            }
            let (_, dq) = q.eval_d(tt);
            if dq == 0.0 {
                break;
            }
            let tn = (tt - ft / dq).clamp(-1.0, 1.0);
            let fnew = f(w_of(tn));
            if fnew.is_nan() || fnew.abs() >= ft.abs() {
                break;
            }
            tt = tn;
            ft = fnew;
        }
        if ft.is_nan() || ft.abs() > 1e-8 * scale.max(1e-300) {
            return None;
        }
        Some(w_of(tt))
    };
    if set == RootSet::AnyOne && half > 0.0 {
        // A sign change over the window brackets a root: refine it inside the bracket (the
        // bracket shrinks at every step whether or not q is monotone there). It is not
        // polished on f: the caller verifies the profile it gives and asks for every
        // (polished) root if that fails.
        let (fl, fr) = (q.eval(-1.0), q.eval(1.0));
        if fl != 0.0 && fr != 0.0 && (fl > 0.0) != (fr > 0.0) {
            out.push(w_of(monotone_root(
                &q,
                -1.0,
                fl,
                1.0,
                fr,
                4.0 * f64::EPSILON,
            )));
            return true;
        }
    }
    if set == RootSet::Single && half > 0.0 {
        let (fl, fr) = (q.eval(-1.0), q.eval(1.0));
        if fl != 0.0 && fr != 0.0 && (fl > 0.0) != (fr > 0.0) {
            let tr = monotone_root(&q, -1.0, fl, 1.0, fr, 4.0 * f64::EPSILON);
            let Some(w) = polish(tr) else {
                return false;
            };
            out.push(w);
            return true;
        }
    }
    let mut r = [0.0; MAX_DEGREE];
    let nr = real_roots(&q, -1.0, 1.0, &mut r);
    let mut polished = [0.0; MAX_DEGREE];
    for (k, &tr) in r[..nr].iter().enumerate() {
        match polish(tr) {
            Some(w) => polished[k] = w,
            None => return false,
        }
    }
    for &w in &polished[..nr] {
        out.push(w);
    }
    true
}

/// All roots of `f` on `[wl, wr]`, where `f` is known to be a polynomial of degree `n ≤ 6` in
/// `w` (by the algebra of the calling family). `n + 1` Chebyshev evaluations give the
/// polynomial, one more evaluation checks it; the roots are polished by Newton steps on `f`
/// itself (with the polynomial's derivative) and pushed to `out`. Returns `false`, leaving `out`
/// unchanged, if a value is not finite or the check fails; the caller then falls back to
/// [`super::roots::scan`].
pub(crate) fn polynomial_roots<F: FnMut(f64) -> f64>(
    f: &mut F,
    wl: f64,
    wr: f64,
    n: usize,
    out: &mut Roots,
) -> bool {
    if !(wl.is_finite() && wr.is_finite() && wr > wl) || n == 0 || n > MAX_DEGREE {
        return false;
    }
    let mid = 0.5 * (wl + wr);
    let half = 0.5 * (wr - wl);
    let w_of = |t: f64| (mid + half * t).clamp(wl, wr);
    let t = CHEBYSHEV[n];
    let mut y = [0.0; MAX_DEGREE + 1];
    let mut ymax = 0.0_f64;
    for k in 0..=n {
        y[k] = f(w_of(t[k]));
        if !y[k].is_finite() {
            return false;
        }
        ymax = ymax.max(y[k].abs());
    }
    let p = interpolate(n, &t, &y);
    // Check at a point that is no node of any degree ≤ 6.
    const T_CHECK: f64 = 0.412_345;
    let yc = f(w_of(T_CHECK));
    if !yc.is_finite() || (yc - p.eval(T_CHECK)).abs() > 1e-9 * (ymax + yc.abs()) + 1e-300 {
        return false;
    }
    let mut r = [0.0; MAX_DEGREE];
    let nr = real_roots(&p, -1.0, 1.0, &mut r);
    for &tr in &r[..nr] {
        // Newton polish on f, in t, with the interpolant's slope.
        let mut tt = tr;
        let mut ft = f(w_of(tt));
        for _ in 0..3 {
            let (_, dp) = p.eval_d(tt);
            if ft == 0.0 || dp == 0.0 || !ft.is_finite() {
                break;
            }
            let tn = (tt - ft / dp).clamp(-1.0, 1.0);
            let fnew = f(w_of(tn));
            if fnew.is_nan() || fnew.abs() >= ft.abs() {
                break;
            }
            tt = tn;
            ft = fnew;
            if ft.abs() <= 1e-15 * ymax {
                break;
            }
        }
        out.push(w_of(tt));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn from_roots(r: &[f64]) -> Poly {
        let mut c = [0.0; MAX_DEGREE + 1];
        c[0] = 1.0;
        for (deg, &x) in r.iter().enumerate() {
            for i in (1..=deg + 1).rev() {
                c[i] = c[i - 1] - x * c[i];
            }
            c[0] *= -x;
        }
        Poly { n: r.len(), c }
    }

    #[test]
    fn interpolation_is_exact_for_polynomials() {
        let p = from_roots(&[-0.9, -0.2, 0.1, 0.5, 0.7, 0.95]);
        let t = CHEBYSHEV[6];
        let y = t.map(|x| p.eval(x));
        let q = interpolate(6, &t, &y);
        for k in 0..=6 {
            assert!(
                (q.c[k] - p.c[k]).abs() < 1e-13,
                "{k}: {} {}",
                q.c[k],
                p.c[k]
            );
        }
    }

    /// The Bernstein coefficients reproduce the polynomial (`Σ b_i C(n,i) s^i (1−s)^(n−i)` with
    /// `t = 2s − 1`), their differences those of the derivative, and the exclusion test never
    /// fires on a polynomial with a root or a near-tangency in `[−1, 1]`.
    #[test]
    fn bernstein_form_is_exact_and_exclusion_is_safe() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..2000 {
            let n = rng.random_range(1..=MAX_DEGREE);
            let mut p = Poly {
                n,
                c: [0.0; MAX_DEGREE + 1],
            };
            for k in 0..=n {
                p.c[k] = rng.random_range(-1.0..1.0);
            }
            let b = bernstein(&p);
            let db = bernstein_derivative(&b, n);
            let bern_eval = |b: &[f64; MAX_DEGREE + 1], m: usize, t: f64| {
                let s = 0.5 * (t + 1.0);
                (0..=m)
                    .map(|i| {
                        b[i] * binomial(m, i) * s.powi(i as i32) * (1.0 - s).powi((m - i) as i32)
                    })
                    .sum::<f64>()
            };
            for k in 0..=20 {
                let t = -1.0 + 0.1 * k as f64;
                assert!(
                    (bern_eval(&b, n, t) - p.eval(t)).abs() < 1e-12,
                    "{p:?} at {t}"
                );
                let dt = p.eval_d(t).1;
                assert!(
                    (bern_eval(&db, n - 1, t) - dt).abs() < 1e-11,
                    "{p:?}' at {t}"
                );
            }
            // Exclusion is only allowed where the polynomial keeps its sign with a margin.
            if bernstein_excludes(&b, n, 0.0) {
                let m = (0..=2000)
                    .map(|k| p.eval(-1.0 + 1e-3 * k as f64))
                    .fold(f64::INFINITY, |m, y| m.min(y.abs()));
                let lo = b[..=n].iter().fold(f64::INFINITY, |m, y| m.min(y.abs()));
                assert!(
                    m >= lo - 1e-12,
                    "{p:?}: min |p| {m} below the hull bound {lo}"
                );
            }
        }
        // Polynomials with roots inside are never excluded, and their roots are all found.
        let p = from_roots(&[-0.3, 0.2, 0.7, 0.9]);
        assert!(!bernstein_excludes(&bernstein(&p), 4, 0.0));
        let mut out = [0.0; MAX_DEGREE];
        assert_eq!(real_roots(&p, -1.0, 1.0, &mut out), 4);
        // No real roots at all: excluded early, none reported.
        let mut q = from_roots(&[]);
        q.n = 4;
        q.c = [2.0, 0.1, 0.3, -0.2, 0.5, 0.0, 0.0];
        assert_eq!(real_roots(&q, -1.0, 1.0, &mut out), 0);
    }

    /// `RootSet::AnyOne` returns one root of a sign-changing window (the same as one of
    /// `RootSet::All`), and every root when the window does not change sign.
    #[test]
    fn any_one_root_is_one_of_all_roots() {
        // (w − 0.2)(w − 0.5)(w − 0.9) on [0, 1]: sign change, three roots.
        let c = [-0.09, 0.73, -1.6, 1.0, 0.0, 0.0, 0.0];
        let mut f = |w: f64| ((w - 1.6) * w + 0.73) * w - 0.09;
        let mut all = Roots::new();
        assert!(closed_form_roots_checked(
            3,
            &c,
            &mut f,
            0.0,
            1.0,
            None,
            RootSet::All,
            &mut all
        ));
        assert_eq!(all.as_slice().len(), 3);
        let mut one = Roots::new();
        assert!(closed_form_roots_checked(
            3,
            &c,
            &mut f,
            0.0,
            1.0,
            None,
            RootSet::AnyOne,
            &mut one
        ));
        assert_eq!(one.as_slice().len(), 1);
        assert!(
            all.as_slice()
                .iter()
                .any(|&x| (x - one.as_slice()[0]).abs() < 1e-14)
        );
        // On [0.1, 0.6] there is no sign change (two roots): all of them are returned.
        let mut two = Roots::new();
        assert!(closed_form_roots_checked(
            3,
            &c,
            &mut f,
            0.1,
            0.6,
            None,
            RootSet::AnyOne,
            &mut two
        ));
        assert_eq!(two.as_slice().len(), 2);
    }

    #[test]
    fn finds_all_roots_including_close_ones() {
        let want = [-0.9, -0.2, 0.1, 0.1001, 0.7, 0.95];
        let p = from_roots(&want);
        let mut out = [0.0; MAX_DEGREE];
        let n = real_roots(&p, -1.0, 1.0, &mut out);
        let mut got = out[..n].to_vec();
        got.sort_by(f64::total_cmp);
        assert_eq!(got.len(), 6, "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{g} {w}");
        }
        // A double root is found at the tangency.
        let p = from_roots(&[0.3, 0.3, -0.5]);
        let n = real_roots(&p, -1.0, 1.0, &mut out);
        assert!(
            out[..n].iter().any(|x| (x - 0.3).abs() < 1e-9),
            "{:?}",
            &out[..n]
        );
    }
}
