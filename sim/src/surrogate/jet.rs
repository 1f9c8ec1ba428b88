//! Second-order jets in ξ: a value with its first and second ξ-derivatives,
//! propagated exactly through sums, products and quotients. The catch-up
//! gate after fracture depends on ξ through the onset depth d*(ξ), so the
//! friction, strain and fracture terms it multiplies carry ξ-derivatives that
//! are easiest to get right by the chain rule done once, here.

/// f(ξ), ∂f/∂ξ and ∂²f/∂ξ² at one ξ.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    /// f.
    pub v: f64,
    /// ∂f/∂ξ.
    pub d: f64,
    /// ∂²f/∂ξ².
    pub dd: f64,
}

impl Jet {
    /// A function of ξ given by its value and derivatives.
    #[inline]
    pub const fn new(v: f64, d: f64, dd: f64) -> Self {
        Self { v, d, dd }
    }

    /// A constant in ξ.
    #[inline]
    pub const fn constant(v: f64) -> Self {
        Self { v, d: 0.0, dd: 0.0 }
    }

    /// self + o.
    #[inline]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.v + o.v, self.d + o.d, self.dd + o.dd)
    }

    /// k·self for a constant k.
    #[inline]
    pub fn scale(self, k: f64) -> Self {
        Self::new(k * self.v, k * self.d, k * self.dd)
    }

    /// self·o (Leibniz).
    #[inline]
    pub fn mul(self, o: Self) -> Self {
        Self::new(
            self.v * o.v,
            self.d * o.v + self.v * o.d,
            self.dd * o.v + 2.0 * self.d * o.d + self.v * o.dd,
        )
    }

    /// 1/self.
    #[inline]
    pub fn recip(self) -> Self {
        let i = 1.0 / self.v;
        let i2 = i * i;
        Self::new(
            i,
            -self.d * i2,
            2.0 * self.d * self.d * i2 * i - self.dd * i2,
        )
    }

    /// f(self) for f given by (f, f', f'') at self's value (chain rule).
    #[inline]
    pub fn compose(self, f: f64, df: f64, ddf: f64) -> Self {
        Self::new(f, df * self.d, ddf * self.d * self.d + df * self.dd)
    }
}
