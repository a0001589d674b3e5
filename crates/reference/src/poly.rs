//! Polynomials in the monomial basis `{1, t, t², …, t^g}` (seeds/000, "Monombasis").

use std::ops::{Add, Mul, Sub};

/// Evaluates `f(t) = Σ a_i t^i` the naive way of seeds/000 ("Standardauswertung"): every power
/// `M_i = t^i` is formed by repeated multiplication, then `f += a_i M_i`. Deliberately *not*
/// Horner, so that it is an independent check of Horner evaluators. `0` for empty `coeffs`.
///
/// ```
/// // seeds/000: f(t) = 2 - 12t + 33t² - 22t³ at t = 1 is 1.
/// assert_eq!(strak_ref::poly_eval(&[2.0, -12.0, 33.0, -22.0], 1.0), 1.0);
/// ```
pub fn poly_eval(coeffs: &[f64], t: f64) -> f64 {
    let Some(&a0) = coeffs.first() else {
        return 0.0;
    };
    let mut f = a0;
    for i in 1..coeffs.len() {
        let mut m = t;
        for _ in 2..=i {
            m *= t;
        }
        f += coeffs[i] * m;
    }
    f
}

/// A polynomial `Σ a_i t^i` given by its monomial coefficients `coeffs[i] = a_i`.
///
/// Trailing zero coefficients are allowed and kept; [`Poly::degree`] ignores them.
///
/// ```
/// use strak_ref::Poly;
/// let p = &Poly::from_root(1.0) * &Poly::from_root(2.0); // (t - 1)(t - 2)
/// assert_eq!(p.coeffs, vec![2.0, -3.0, 1.0]);
/// assert_eq!(p.eval(3.0), 2.0);
/// assert_eq!(p.derivative().coeffs, vec![-3.0, 2.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Poly {
    /// Monomial coefficients, `coeffs[i]` multiplies `t^i`.
    pub coeffs: Vec<f64>,
}

impl Poly {
    /// The polynomial with the given monomial coefficients.
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::new(vec![1.0, 2.0]).eval(2.0), 5.0);
    /// ```
    pub fn new(coeffs: Vec<f64>) -> Self {
        Self { coeffs }
    }

    /// The constant polynomial `c`.
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::constant(3.0).eval(10.0), 3.0);
    /// ```
    pub fn constant(c: f64) -> Self {
        Self { coeffs: vec![c] }
    }

    /// The linear factor `t − a`.
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::from_root(2.0).coeffs, vec![-2.0, 1.0]);
    /// ```
    pub fn from_root(a: f64) -> Self {
        Self {
            coeffs: vec![-a, 1.0],
        }
    }

    /// The degree: index of the highest non-zero coefficient (`0` for the zero polynomial).
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::new(vec![1.0, 2.0, 0.0]).degree(), 1);
    /// ```
    pub fn degree(&self) -> usize {
        self.coeffs.iter().rposition(|&c| c != 0.0).unwrap_or(0)
    }

    /// Value at `t` by [`poly_eval`] (naive power sum, not Horner).
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::new(vec![0.0, 0.0, 1.0]).eval(3.0), 9.0);
    /// ```
    pub fn eval(&self, t: f64) -> f64 {
        poly_eval(&self.coeffs, t)
    }

    /// The derivative `Σ i a_i t^{i−1}` (the zero polynomial `[0]` for constants).
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::new(vec![5.0, 1.0, 1.0]).derivative().coeffs, vec![1.0, 2.0]);
    /// ```
    pub fn derivative(&self) -> Self {
        if self.coeffs.len() <= 1 {
            return Self::constant(0.0);
        }
        Self {
            coeffs: (1..self.coeffs.len())
                .map(|i| i as f64 * self.coeffs[i])
                .collect(),
        }
    }

    /// The `k`-th derivative (`k = 0` is a copy).
    ///
    /// ```
    /// let p = strak_ref::Poly::new(vec![0.0, 0.0, 0.0, 1.0]); // t³
    /// assert_eq!(p.nth_derivative(2).coeffs, vec![0.0, 6.0]);
    /// assert_eq!(p.nth_derivative(4).coeffs, vec![0.0]);
    /// ```
    pub fn nth_derivative(&self, k: usize) -> Self {
        let mut p = self.clone();
        for _ in 0..k {
            p = p.derivative();
        }
        p
    }

    /// The polynomial multiplied by the scalar `s`.
    ///
    /// ```
    /// assert_eq!(strak_ref::Poly::new(vec![1.0, 2.0]).scale(0.5).coeffs, vec![0.5, 1.0]);
    /// ```
    pub fn scale(&self, s: f64) -> Self {
        Self {
            coeffs: self.coeffs.iter().map(|c| s * c).collect(),
        }
    }

    /// `self` raised to the power `e` by repeated multiplication (`p⁰ = 1`).
    ///
    /// ```
    /// let p = strak_ref::Poly::new(vec![1.0, -1.0]).pow(2); // (1 - t)²
    /// assert_eq!(p.coeffs, vec![1.0, -2.0, 1.0]);
    /// ```
    pub fn pow(&self, e: u32) -> Self {
        let mut p = Self::constant(1.0);
        for _ in 0..e {
            p = &p * self;
        }
        p
    }
}

impl Mul<&Poly> for &Poly {
    type Output = Poly;

    /// The product by the Cauchy product of the coefficient vectors.
    fn mul(self, rhs: &Poly) -> Poly {
        if self.coeffs.is_empty() || rhs.coeffs.is_empty() {
            return Poly::constant(0.0);
        }
        let mut c = vec![0.0; self.coeffs.len() + rhs.coeffs.len() - 1];
        for (i, a) in self.coeffs.iter().enumerate() {
            for (j, b) in rhs.coeffs.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly { coeffs: c }
    }
}

impl Add<&Poly> for &Poly {
    type Output = Poly;

    /// The coefficient-wise sum.
    fn add(self, rhs: &Poly) -> Poly {
        let n = self.coeffs.len().max(rhs.coeffs.len());
        Poly {
            coeffs: (0..n)
                .map(|i| {
                    self.coeffs.get(i).copied().unwrap_or(0.0)
                        + rhs.coeffs.get(i).copied().unwrap_or(0.0)
                })
                .collect(),
        }
    }
}

impl Sub<&Poly> for &Poly {
    type Output = Poly;

    /// The coefficient-wise difference.
    fn sub(self, rhs: &Poly) -> Poly {
        self + &rhs.scale(-1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn naive_eval_matches_seed_example() {
        // seeds/000: t(2 + t²) − 1 = 2t + t³ − 1.
        let p = Poly::new(vec![-1.0, 2.0, 0.0, 1.0]);
        for &t in &[-2.0, -0.5, 0.0, 0.3, 1.0, 2.5] {
            let direct: f64 = t * (2.0 + t * t) - 1.0;
            assert!((p.eval(t) - direct).abs() < 1e-13);
        }
        assert_eq!(poly_eval(&[], 3.0), 0.0);
        assert_eq!(poly_eval(&[4.0], 3.0), 4.0);
    }

    #[test]
    fn product_sum_and_derivative() {
        let p = Poly::new(vec![1.0, 1.0]); // 1 + t
        let q = Poly::new(vec![-1.0, 1.0]); // -1 + t
        assert_eq!((&p * &q).coeffs, vec![-1.0, 0.0, 1.0]);
        assert_eq!((&p + &q).coeffs, vec![0.0, 2.0]);
        assert_eq!((&p - &q).coeffs, vec![2.0, 0.0]);
        let cube = p.pow(3); // 1 + 3t + 3t² + t³
        assert_eq!(cube.coeffs, vec![1.0, 3.0, 3.0, 1.0]);
        assert_eq!(cube.derivative().coeffs, vec![3.0, 6.0, 3.0]);
        assert_eq!(cube.nth_derivative(3).coeffs, vec![6.0]);
        assert_eq!(cube.degree(), 3);
        assert_eq!(Poly::constant(0.0).degree(), 0);
    }
}
