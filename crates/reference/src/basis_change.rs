//! Basis change between the monomial and the Bernstein basis (seeds/000,
//! "Basistransformation", "Beispieltransformation").
//!
//! Notation of the seed: `B^g(t) = A_{B←M} M^g(t)` relates the *bases*; the *coefficient
//! vectors* transform by `b = T_{B←M} a` and `a = T_{M←B} b` with `T_{M←B} = A_{B←M}ᵀ` and
//! `T_{B←M} = (A_{B←M}ᵀ)⁻¹`.

use crate::combinatorics::binomial;
use crate::linalg::{invert, mat_vec, transpose};
use crate::poly::Poly;

/// The matrix `A_{B←M}` of degree `g`, read off by expanding each Bernstein polynomial
/// `B_i^g(t) = C(g, i) (1−t)^{g−i} t^i` into monomials (seeds/000): row `i` holds the monomial
/// coefficients of `B_i^g`, so `A[i][j]` is the coefficient of `t^j` in `B_i^g`.
///
/// ```
/// let a = strak_ref::a_bernstein_from_monomial(2);
/// assert_eq!(a, vec![vec![1.0, -2.0, 1.0], vec![0.0, 2.0, -2.0], vec![0.0, 0.0, 1.0]]);
/// ```
pub fn a_bernstein_from_monomial(g: usize) -> Vec<Vec<f64>> {
    let one_minus_t = Poly::new(vec![1.0, -1.0]);
    let t = Poly::new(vec![0.0, 1.0]);
    (0..=g)
        .map(|i| {
            let b = (&one_minus_t.pow((g - i) as u32) * &t.pow(i as u32))
                .scale(binomial(g as u32, i as u32));
            let mut row = b.coeffs;
            row.resize(g + 1, 0.0);
            row
        })
        .collect()
}

/// `T_{M←B} = A_{B←M}ᵀ` of degree `g`: maps Bernstein coefficients to monomial coefficients
/// (`a = T_{M←B} b`, seeds/000).
///
/// ```
/// let t = strak_ref::t_monomial_from_bernstein(1);
/// assert_eq!(t, vec![vec![1.0, 0.0], vec![-1.0, 1.0]]);
/// ```
pub fn t_monomial_from_bernstein(g: usize) -> Vec<Vec<f64>> {
    transpose(&a_bernstein_from_monomial(g))
}

/// `T_{B←M} = (A_{B←M}ᵀ)⁻¹` of degree `g`, computed with [`invert`]: maps monomial coefficients
/// to Bernstein coefficients (`b = T_{B←M} a`, seeds/000).
///
/// # Panics
/// Never for the (always regular, triangular) `A_{B←M}`; an `expect` guards the inversion.
///
/// ```
/// let t = strak_ref::t_bernstein_from_monomial(1);
/// assert_eq!(t, vec![vec![1.0, 0.0], vec![1.0, 1.0]]);
/// ```
pub fn t_bernstein_from_monomial(g: usize) -> Vec<Vec<f64>> {
    invert(&t_monomial_from_bernstein(g)).expect("A_{B<-M} is regular (unit diagonal up to C(g,i))")
}

/// Monomial coefficients `a = T_{M←B} b` of the polynomial with Bernstein coefficients `b`
/// (degree `b.len() − 1`).
///
/// ```
/// // seeds/000 example (see the crate tests for the seed's misprinted last entry).
/// let a = strak_ref::monomial_from_bernstein(&[2.0, -2.0, 5.0, 1.0]);
/// assert_eq!(a, vec![2.0, -12.0, 33.0, -22.0]);
/// ```
pub fn monomial_from_bernstein(b: &[f64]) -> Vec<f64> {
    if b.is_empty() {
        return Vec::new();
    }
    mat_vec(&t_monomial_from_bernstein(b.len() - 1), b)
}

/// Bernstein coefficients `b = T_{B←M} a` of the polynomial with monomial coefficients `a`
/// (degree `a.len() − 1`).
///
/// ```
/// // t in degree 3: b = (0, 1/3, 2/3, 1).
/// let b = strak_ref::bernstein_from_monomial(&[0.0, 1.0, 0.0, 0.0]);
/// assert!((b[1] - 1.0 / 3.0).abs() < 1e-15 && (b[2] - 2.0 / 3.0).abs() < 1e-15);
/// ```
pub fn bernstein_from_monomial(a: &[f64]) -> Vec<f64> {
    if a.is_empty() {
        return Vec::new();
    }
    mat_vec(&t_bernstein_from_monomial(a.len() - 1), a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::bernstein;
    use crate::poly::poly_eval;

    #[test]
    fn a_matrix_degree_3_of_seed() {
        let a = a_bernstein_from_monomial(3);
        let expect = vec![
            vec![1.0, -3.0, 3.0, -1.0],
            vec![0.0, 3.0, -6.0, 3.0],
            vec![0.0, 0.0, 3.0, -3.0],
            vec![0.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(a, expect);
    }

    #[test]
    fn t_bernstein_from_monomial_degree_3_of_seed() {
        let t = t_bernstein_from_monomial(3);
        let third = 1.0 / 3.0;
        let expect = [
            [1.0, 0.0, 0.0, 0.0],
            [1.0, third, 0.0, 0.0],
            [1.0, 2.0 * third, third, 0.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    (t[i][j] - expect[i][j]).abs() < 1e-15,
                    "T[{i}][{j}] = {}",
                    t[i][j]
                );
            }
        }
    }

    #[test]
    fn seed_example_bernstein_2_m2_5_1() {
        // seeds/000 prints the result as (2, −12, 33, −23), but its own expansion
        // 2(1−t)³ − 6t(1−t)² + 15t²(1−t) + t³ sums to −2 − 6 − 15 + 1 = −22 for t³, and
        // f(1) = b_3 = 1 requires 2 − 12 + 33 + a_3 = 1, i.e. a_3 = −22. The seed's −23 is a
        // misprint; we assert the correct value and that −23 is wrong.
        let b = [2.0, -2.0, 5.0, 1.0];
        let a = monomial_from_bernstein(&b);
        assert_eq!(a, vec![2.0, -12.0, 33.0, -22.0]);
        assert_eq!(poly_eval(&a, 1.0), 1.0);
        assert_ne!(poly_eval(&[2.0, -12.0, 33.0, -23.0], 1.0), 1.0);
        for j in 0..=10 {
            let t = j as f64 / 10.0;
            let f: f64 = (0..4).map(|i| b[i] * bernstein(i, 3, t)).sum();
            assert!((poly_eval(&a, t) - f).abs() < 1e-13);
        }
        let back = bernstein_from_monomial(&a);
        for i in 0..4 {
            assert!((back[i] - b[i]).abs() < 1e-13);
        }
    }

    #[test]
    fn round_trip_higher_degrees() {
        for g in 0..=7 {
            let a: Vec<f64> = (0..=g).map(|i| (i as f64 * 0.7).sin() + 0.1).collect();
            let b = bernstein_from_monomial(&a);
            for j in 0..=8 {
                let t = j as f64 / 8.0;
                let fb: f64 = (0..=g).map(|i| b[i] * bernstein(i, g, t)).sum();
                assert!((fb - poly_eval(&a, t)).abs() < 1e-12);
            }
        }
        assert!(monomial_from_bernstein(&[]).is_empty());
        assert!(bernstein_from_monomial(&[]).is_empty());
    }
}
