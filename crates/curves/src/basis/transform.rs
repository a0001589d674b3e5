//! Basis changes between the monomial and the Bernstein basis for any degree `g = N − 1`
//! (Farin, *Curves and Surfaces for CAGD*, 5th ed., §4.8 "The Matrix Form of a Bézier
//! Curve").
//!
//! The formulas, their derivation and a worked example are documented in the
//! [`basis`](crate::basis) module docs ("Basis changes").

use super::bernstein::binomial_f64;
use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// `T_{M←B}[j][i] = (−1)^{j−i} C(g,j) C(j,i)` for `i ≤ j`, else 0.
fn monomial_from_bernstein_entry(g: usize, j: usize, i: usize) -> f64 {
    if i > j {
        return 0.0;
    }
    let v = binomial_f64(g, j) * binomial_f64(j, i);
    if (j - i) % 2 == 1 { -v } else { v }
}

/// `T_{B←M}[i][j] = C(i,j) / C(g,j)` for `j ≤ i`, else 0.
fn bernstein_from_monomial_entry(g: usize, i: usize, j: usize) -> f64 {
    if j > i {
        return 0.0;
    }
    binomial_f64(i, j) / binomial_f64(g, j)
}

fn matrix_from<S: Scalar, const N: usize>(
    entry: impl Fn(usize, usize) -> f64,
) -> Result<[[S; N]; N], Error> {
    let mut ok = true;
    let m = core::array::from_fn(|r| {
        core::array::from_fn(|c| {
            S::from_f64(entry(r, c)).unwrap_or_else(|| {
                ok = false;
                S::ZERO
            })
        })
    });
    if ok { Ok(m) } else { Err(Error::OutOfRange) }
}

/// The coefficient transformation `T_{M←B}` (Bernstein → monomial) of degree `g = N − 1`:
/// `a⃗ = T_{M←B} b⃗`, entries `T[j][i] = (−1)^{j−i} C(g,j) C(j,i)` (see the
/// [`basis`](crate::basis) module docs for the derivation).
///
/// # Errors
/// [`Error::OutOfRange`] when an entry does not fit the scalar type.
///
/// ```
/// use strak_curves::basis::bernstein_to_monomial_matrix;
/// // A_{B←M}ᵀ for g = 3
/// let t = bernstein_to_monomial_matrix::<f64, 4>()?;
/// assert_eq!(t, [
///     [1.0, 0.0, 0.0, 0.0],
///     [-3.0, 3.0, 0.0, 0.0],
///     [3.0, -6.0, 3.0, 0.0],
///     [-1.0, 3.0, -3.0, 1.0],
/// ]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn bernstein_to_monomial_matrix<S: Scalar, const N: usize>() -> Result<[[S; N]; N], Error> {
    let g = N.saturating_sub(1);
    matrix_from(|j, i| monomial_from_bernstein_entry(g, j, i))
}

/// The coefficient transformation `T_{B←M}` (monomial → Bernstein) of degree `g = N − 1`:
/// `b⃗ = T_{B←M} a⃗`, entries `T[i][j] = C(i,j) / C(g,j)` (see the [`basis`](crate::basis) module docs).
///
/// # Errors
/// [`Error::OutOfRange`] when an entry cannot be represented (only for absurd degrees; the
/// entries lie in `[0, 1]`).
///
/// ```
/// use strak_curves::basis::monomial_to_bernstein_matrix;
/// // g = 3
/// let t = monomial_to_bernstein_matrix::<f64, 4>()?;
/// assert_eq!(t, [
///     [1.0, 0.0, 0.0, 0.0],
///     [1.0, 1.0 / 3.0, 0.0, 0.0],
///     [1.0, 2.0 / 3.0, 1.0 / 3.0, 0.0],
///     [1.0, 1.0, 1.0, 1.0],
/// ]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn monomial_to_bernstein_matrix<S: Scalar, const N: usize>() -> Result<[[S; N]; N], Error> {
    let g = N.saturating_sub(1);
    matrix_from(|i, j| bernstein_from_monomial_entry(g, i, j))
}

/// The basis matrix `A_{B←M}` with `B⃗^g(t) = A_{B←M} M⃗^g(t)`: row `i` holds the
/// monomial coefficients of `B_i^g`, `A[i][j] = (−1)^{j−i} C(g,j) C(j,i)`. It is the
/// transpose of [`bernstein_to_monomial_matrix`].
///
/// # Errors
/// [`Error::OutOfRange`] when an entry does not fit the scalar type.
///
/// ```
/// use strak_curves::basis::bernstein_basis_matrix;
/// let a = bernstein_basis_matrix::<f64, 4>()?;
/// assert_eq!(a[1], [0.0, 3.0, -6.0, 3.0]); // 3(1−t)²t = 3t − 6t² + 3t³
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn bernstein_basis_matrix<S: Scalar, const N: usize>() -> Result<[[S; N]; N], Error> {
    let g = N.saturating_sub(1);
    matrix_from(|i, j| monomial_from_bernstein_entry(g, j, i))
}

/// `a⃗ = T_{M←B} b⃗` in `f64`, summed in ascending `i` with integer products.
pub(crate) fn bernstein_to_monomial_f64<const N: usize>(b: &[f64; N]) -> [f64; N] {
    let g = N.saturating_sub(1);
    core::array::from_fn(|j| {
        let mut v = 0.0;
        for (i, &bi) in b.iter().enumerate().take(j + 1) {
            v += monomial_from_bernstein_entry(g, j, i) * bi;
        }
        v
    })
}

/// `b⃗ = T_{B←M} a⃗` in `f64`, each term formed as `(C(i,j) · a_j) / C(g,j)` so that exact
/// results stay exact.
pub(crate) fn monomial_to_bernstein_f64<const N: usize>(a: &[f64; N]) -> [f64; N] {
    let g = N.saturating_sub(1);
    core::array::from_fn(|i| {
        let mut v = 0.0;
        for (j, &aj) in a.iter().enumerate().take(i + 1) {
            v += binomial_f64(i, j) * aj / binomial_f64(g, j);
        }
        v
    })
}

/// Applies a coordinate-wise `f64` map to points, rounding each result once to the scalar.
pub(crate) fn map_coordinates<P: Point, const N: usize>(
    src: &[P; N],
    f: impl Fn(&[f64; N]) -> [f64; N],
) -> Result<[P; N], Error> {
    if !src.iter().all(|p| p.is_finite()) {
        return Err(Error::NonFinite);
    }
    let mut out = [P::zero(); N];
    for c in 0..P::DIM {
        let x = src.map(|p| p.coord(c).to_f64());
        let y = f(&x);
        for (o, &v) in out.iter_mut().zip(y.iter()) {
            let s = P::Scalar::from_f64(v).ok_or(Error::OutOfRange)?;
            let old = *o;
            *o = P::from_coords(|d| if d == c { s } else { old.coord(d) });
        }
    }
    Ok(out)
}

/// Converts Bernstein coefficients (Bézier points) `b⃗` to monomial coefficients
/// `a⃗ = T_{M←B} b⃗`, coordinate-wise (in matrix form the control point
/// matrix is transformed like a coefficient vector, Farin §4.8).
///
/// # Errors
/// [`Error::NonFinite`] for NaN/∞ input, [`Error::OutOfRange`] when a coefficient does not fit
/// the scalar type.
///
/// ```
/// use strak_curves::basis::bernstein_to_monomial;
/// // the worked example of the `basis` module docs
/// let a = bernstein_to_monomial(&[[2.0], [-2.0], [5.0], [1.0]])?;
/// assert_eq!(a, [[2.0], [-12.0], [33.0], [-22.0]]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn bernstein_to_monomial<P: Point, const N: usize>(b: &[P; N]) -> Result<[P; N], Error> {
    map_coordinates(b, bernstein_to_monomial_f64)
}

/// Converts monomial coefficients `a⃗` to Bernstein coefficients (Bézier points)
/// `b⃗ = T_{B←M} a⃗`, coordinate-wise.
///
/// # Errors
/// [`Error::NonFinite`] for NaN/∞ input, [`Error::OutOfRange`] when a coefficient does not fit
/// the scalar type.
///
/// ```
/// use strak_curves::basis::monomial_to_bernstein;
/// let b = monomial_to_bernstein(&[[2.0], [-12.0], [33.0], [-22.0]])?;
/// assert_eq!(b, [[2.0], [-2.0], [5.0], [1.0]]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
pub fn monomial_to_bernstein<P: Point, const N: usize>(a: &[P; N]) -> Result<[P; N], Error> {
    map_coordinates(a, monomial_to_bernstein_f64)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
mod tests {
    use super::*;
    use crate::basis::{bernstein_all, horner, monomials};
    use crate::{I16F16, I32F32};
    use glam::DVec2;

    #[test]
    fn matrices_degree_3() {
        let tbm = monomial_to_bernstein_matrix::<f64, 4>().unwrap();
        assert_eq!(
            tbm,
            [
                [1.0, 0.0, 0.0, 0.0],
                [1.0, 1.0 / 3.0, 0.0, 0.0],
                [1.0, 2.0 / 3.0, 1.0 / 3.0, 0.0],
                [1.0, 1.0, 1.0, 1.0]
            ]
        );
        let a = bernstein_basis_matrix::<f64, 4>().unwrap();
        assert_eq!(
            a,
            [
                [1.0, -3.0, 3.0, -1.0],
                [0.0, 3.0, -6.0, 3.0],
                [0.0, 0.0, 3.0, -3.0],
                [0.0, 0.0, 0.0, 1.0]
            ]
        );
        let tmb = bernstein_to_monomial_matrix::<f64, 4>().unwrap();
        for i in 0..4 {
            for j in 0..4 {
                assert_eq!(tmb[i][j], a[j][i]);
            }
        }
    }

    #[test]
    fn worked_example_bernstein_to_monomial_and_back() {
        // b = (2, −2, 5, 1): the cubic coefficient is −2 − 6 − 15 + 1 = −22 (f(1) = b_3 = 1).
        let a = bernstein_to_monomial_f64(&[2.0, -2.0, 5.0, 1.0]);
        assert_eq!(a, [2.0, -12.0, 33.0, -22.0]);
        assert_eq!(monomial_to_bernstein_f64(&a), [2.0, -2.0, 5.0, 1.0]);
        // the polynomial agrees with the Bernstein sum, and f(1) = b_3 = 1
        assert_eq!(horner(&a, 1.0), 1.0);
        for step in 0..=8 {
            let t = step as f64 / 8.0;
            let bern: f64 = bernstein_all::<f64, 4>(t)
                .iter()
                .zip([2.0, -2.0, 5.0, 1.0])
                .map(|(x, y)| x * y)
                .sum();
            assert!((horner(&a, t) - bern).abs() < 1e-14);
        }
        // a⃗ = T_{M←B} b⃗ with the matrix, exactly
        let tmb = bernstein_to_monomial_matrix::<f64, 4>().unwrap();
        let b = [2.0, -2.0, 5.0, 1.0];
        let am: [f64; 4] = core::array::from_fn(|j| (0..4).map(|i| tmb[j][i] * b[i]).sum());
        assert_eq!(am, [2.0, -12.0, 33.0, -22.0]);
        // with points
        let p =
            bernstein_to_monomial(&[[2.0_f64, 0.0], [-2.0, 1.0], [5.0, 2.0], [1.0, 3.0]]).unwrap();
        assert_eq!(p, [[2.0, 0.0], [-12.0, 3.0], [33.0, 0.0], [-22.0, 0.0]]);
        assert_eq!(
            monomial_to_bernstein(&p).unwrap(),
            [[2.0, 0.0], [-2.0, 1.0], [5.0, 2.0], [1.0, 3.0]]
        );
    }

    #[test]
    fn matrices_are_inverse_and_basis_matrix_maps_monomials_to_bernstein() {
        fn check<const N: usize>() {
            let tmb = bernstein_to_monomial_matrix::<f64, N>().unwrap();
            let tbm = monomial_to_bernstein_matrix::<f64, N>().unwrap();
            for i in 0..N {
                for j in 0..N {
                    let p: f64 = (0..N).map(|k| tmb[i][k] * tbm[k][j]).sum();
                    let e = if i == j { 1.0 } else { 0.0 };
                    assert!((p - e).abs() < 1e-12, "N={N} ({i},{j}): {p}");
                }
            }
            let a = bernstein_basis_matrix::<f64, N>().unwrap();
            for step in 0..=10 {
                let t = step as f64 / 10.0;
                let m = monomials::<f64, N>(t);
                let b = bernstein_all::<f64, N>(t);
                for i in 0..N {
                    let v: f64 = (0..N).map(|j| a[i][j] * m[j]).sum();
                    assert!((v - b[i]).abs() < 1e-12);
                }
            }
        }
        check::<1>();
        check::<2>();
        check::<3>();
        check::<5>();
        check::<8>();
    }

    #[test]
    fn point_round_trip() {
        let b = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.5, 2.0),
            DVec2::new(-0.5, 3.0),
            DVec2::new(4.0, -1.0),
            DVec2::new(2.0, 2.5),
        ];
        let a = bernstein_to_monomial(&b).unwrap();
        let back = monomial_to_bernstein(&a).unwrap();
        for (x, y) in b.iter().zip(back.iter()) {
            assert!((*x - *y).length() < 1e-13);
        }
    }

    #[test]
    fn fixed_point_and_f32_matrices_agree_with_f64() {
        let r = monomial_to_bernstein_matrix::<f64, 6>().unwrap();
        let x = monomial_to_bernstein_matrix::<I16F16, 6>().unwrap();
        let y = monomial_to_bernstein_matrix::<I32F32, 6>().unwrap();
        let f = monomial_to_bernstein_matrix::<f32, 6>().unwrap();
        for i in 0..6 {
            for j in 0..6 {
                assert!((x[i][j].to_f64() - r[i][j]).abs() <= <I16F16 as Scalar>::EPSILON / 2.0);
                assert!((y[i][j].to_f64() - r[i][j]).abs() <= <I32F32 as Scalar>::EPSILON / 2.0);
                assert!((f64::from(f[i][j]) - r[i][j]).abs() <= 1e-7);
            }
        }
        // integer entries are exact
        let tx = bernstein_to_monomial_matrix::<I16F16, 12>().unwrap();
        let tr = bernstein_to_monomial_matrix::<f64, 12>().unwrap();
        for i in 0..12 {
            for j in 0..12 {
                assert_eq!(tx[i][j].to_f64(), tr[i][j]);
            }
        }
        // fixed-point point conversion of the worked example is exact
        let bx = [2.0, -2.0, 5.0, 1.0].map(|v| [I16F16::from_num(v)]);
        let ax = bernstein_to_monomial(&bx).unwrap();
        assert_eq!(ax.map(|p| p[0].to_f64()), [2.0, -12.0, 33.0, -22.0]);
        assert_eq!(monomial_to_bernstein(&ax).unwrap(), bx);
    }

    #[test]
    fn error_out_of_range() {
        // g = 12: the entry 12!/(4!4!4!) = 34 650 exceeds I16F16's limit 16 383
        assert_eq!(
            bernstein_to_monomial_matrix::<I16F16, 13>(),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            bernstein_basis_matrix::<I16F16, 13>(),
            Err(Error::OutOfRange)
        );
        assert!(bernstein_to_monomial_matrix::<I32F32, 13>().is_ok());
        assert!(monomial_to_bernstein_matrix::<I16F16, 13>().is_ok());
        // points: alternating Bézier points make a large monomial coefficient
        let b = [10000.0, -10000.0, 10000.0].map(|v| [I16F16::from_num(v)]);
        assert_eq!(bernstein_to_monomial(&b), Err(Error::OutOfRange));
        let a = [0.0, 0.0, 1.0e4, 1.0e4].map(|v| [I16F16::from_num(v)]);
        assert_eq!(monomial_to_bernstein(&a), Err(Error::OutOfRange));
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            bernstein_to_monomial(&[[1.0], [f64::NAN]]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            monomial_to_bernstein(&[[f32::INFINITY], [1.0]]),
            Err(Error::NonFinite)
        );
    }
}
