//! O(n) solvers for tridiagonal and cyclic tridiagonal linear systems (the systems of
//! interpolating cubic splines), in caller-provided storage: the Thomas algorithm (Burden &
//! Faires, *Numerical Analysis*, §6.6, Crout factorization of a tridiagonal matrix; Press et
//! al., *Numerical Recipes*, 3rd ed., §2.4) and, for the cyclic case, the Sherman–Morrison
//! correction (Numerical Recipes §2.7).
//!
//! The matrix is given by three equally long slices: `sub[i]` is the entry in row `i`,
//! column `i − 1`; `diag[i]` the diagonal entry; `sup[i]` the entry in row `i`, column `i + 1`.
//! For the plain solver `sub[0]` and `sup[n − 1]` are ignored; for the cyclic solver they are
//! the corner entries: `sub[0]` in row 0, column `n − 1`, and `sup[n − 1]` in row `n − 1`,
//! column 0.
//!
//! Every arithmetic operation is checked: a division by an exactly zero pivot is
//! [`Error::InvalidArgument`], a result that would leave the scalar's range
//! ([`Scalar::LIMIT`]) is [`Error::OutOfRange`]. So the solvers never panic, in fixed-point
//! neither. They do not pivot: use them for diagonally dominant systems (the spline systems
//! are), for which elimination without pivoting is stable.

use crate::error::Error;
use crate::point::Point;
use crate::scalar::Scalar;

/// Solves the tridiagonal system `A·x = rhs` by the Thomas algorithm (Gaussian elimination
/// without pivoting), in `O(n)`. The solution overwrites `rhs`; `scratch` (at least `n`
/// long) holds the modified super-diagonal.
///
/// # Errors
/// [`Error::LengthMismatch`] when `sub`, `sup` or `rhs` differ in length from `diag`, or
/// `scratch` is shorter; [`Error::NonFinite`] for a NaN or infinite entry;
/// [`Error::InvalidArgument`] for a zero pivot; [`Error::OutOfRange`] when an intermediate
/// value leaves the scalar's range. On error, `rhs` may be partly overwritten.
///
/// ```
/// use strak_curves::solve_tridiagonal;
///
/// // [2 1 0; 1 2 1; 0 1 2] x = [4 8 8]  =>  x = [1 2 3]
/// let sub = [0.0, 1.0, 1.0];
/// let diag = [2.0, 2.0, 2.0];
/// let sup = [1.0, 1.0, 0.0];
/// let mut rhs = [[4.0_f64], [8.0], [8.0]];
/// let mut scratch = [0.0; 3];
/// solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch).unwrap();
/// for (x, want) in rhs.iter().zip([1.0, 2.0, 3.0]) {
///     assert!((x[0] - want).abs() < 1e-15);
/// }
/// ```
pub fn solve_tridiagonal<S: Scalar, P: Point<Scalar = S>>(
    sub: &[S],
    diag: &[S],
    sup: &[S],
    rhs: &mut [P],
    scratch: &mut [S],
) -> Result<(), Error> {
    check_inputs(sub, diag, sup, rhs, scratch.len())?;
    let (first, last) = match (diag.first(), diag.last()) {
        (Some(&f), Some(&l)) => (f, l),
        _ => return Ok(()),
    };
    eliminate(sub, diag, sup, (first, last), rhs, scratch, None)
}

/// Solves the cyclic (periodic) tridiagonal system `A·x = rhs`, where `A` is tridiagonal
/// plus the two corner entries `sub[0]` (row 0, column n − 1) and `sup[n − 1]` (row n − 1,
/// column 0), in `O(n)`: the Sherman–Morrison formula applied to the Thomas algorithm
/// (with `γ = −diag[0]`, as in Numerical Recipes' `cyclic`). The solution overwrites `rhs`;
/// `scratch` and `correction` (each at least `n` long) are working storage.
///
/// For `n = 2` the corner entries add to the off-diagonal ones; for `n = 1` the matrix is
/// the single entry `sub[0] + diag[0] + sup[0]`.
///
/// # Errors
/// As [`solve_tridiagonal`]; also [`Error::InvalidArgument`] when `diag[0]` is zero or the
/// Sherman–Morrison denominator vanishes (singular matrix).
///
/// ```
/// use strak_curves::solve_cyclic_tridiagonal;
///
/// // [4 1 0 1; 1 4 1 0; 0 1 4 1; 1 0 1 4] x = [10 12 18 20]  =>  x = [1 2 3 4]
/// let sub = [1.0, 1.0, 1.0, 1.0];
/// let diag = [4.0, 4.0, 4.0, 4.0];
/// let sup = [1.0, 1.0, 1.0, 1.0];
/// let mut rhs = [[10.0_f64], [12.0], [18.0], [20.0]];
/// let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
/// solve_cyclic_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut a, &mut b).unwrap();
/// for (x, want) in rhs.iter().zip([1.0, 2.0, 3.0, 4.0]) {
///     assert!((x[0] - want).abs() < 1e-12);
/// }
/// ```
pub fn solve_cyclic_tridiagonal<S: Scalar, P: Point<Scalar = S>>(
    sub: &[S],
    diag: &[S],
    sup: &[S],
    rhs: &mut [P],
    scratch: &mut [S],
    correction: &mut [S],
) -> Result<(), Error> {
    check_inputs(sub, diag, sup, rhs, scratch.len().min(correction.len()))?;
    let n = diag.len();
    let (Some(&b0), Some(&bn), Some(&beta), Some(&alpha)) =
        (diag.first(), diag.last(), sub.first(), sup.last())
    else {
        return Ok(());
    };
    if n == 1 {
        let m = add(add(beta, b0)?, alpha)?;
        if let Some(r) = rhs.first_mut() {
            *r = p_div(*r, m)?;
        }
        return Ok(());
    }
    // Sherman–Morrison: A = T + u·vᵀ with u = (γ, 0, …, 0, α), v = (1, 0, …, 0, β/γ).
    let gamma = sub_(S::ZERO, b0)?;
    let first = sub_(b0, gamma)?;
    let last = sub_(bn, div(mul(alpha, beta)?, gamma)?)?;
    for z in correction.iter_mut() {
        *z = S::ZERO;
    }
    if let Some(z) = correction.first_mut() {
        *z = gamma;
    }
    if let Some(z) = correction.get_mut(n - 1) {
        *z = alpha;
    }
    eliminate(
        sub,
        diag,
        sup,
        (first, last),
        rhs,
        scratch,
        Some(correction),
    )?;
    // x = y − (v·y)/(1 + v·z) · z
    let (Some(&y0), Some(&yn), Some(&z0), Some(&zn)) = (
        rhs.first(),
        rhs.get(n - 1),
        correction.first(),
        correction.get(n - 1),
    ) else {
        return Ok(());
    };
    let ratio = div(beta, gamma)?;
    let denom = add(add(S::ONE, z0)?, mul(ratio, zn)?)?;
    let num = p_sub_scaled(y0, -ratio, yn)?;
    let fact = p_div(num, denom)?;
    for (x, &z) in rhs.iter_mut().zip(correction.iter()) {
        *x = p_sub_scaled(*x, z, fact)?;
    }
    Ok(())
}

fn check_inputs<S: Scalar, P: Point<Scalar = S>>(
    sub: &[S],
    diag: &[S],
    sup: &[S],
    rhs: &[P],
    scratch_len: usize,
) -> Result<(), Error> {
    let n = diag.len();
    for found in [sub.len(), sup.len(), rhs.len()] {
        if found != n {
            return Err(Error::LengthMismatch { expected: n, found });
        }
    }
    if scratch_len < n {
        return Err(Error::LengthMismatch {
            expected: n,
            found: scratch_len,
        });
    }
    let finite = sub
        .iter()
        .chain(diag.iter())
        .chain(sup.iter())
        .all(|x| x.is_finite())
        && rhs.iter().all(|p| p.is_finite());
    if finite {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// Forward elimination and back substitution with the diagonal's first and last entries
/// replaced by `ends`; `extra` (if any) is a second, scalar right-hand side solved alongside.
/// Lengths are checked by the caller (`n ≥ 1`).
fn eliminate<S: Scalar, P: Point<Scalar = S>>(
    sub: &[S],
    diag: &[S],
    sup: &[S],
    ends: (S, S),
    rhs: &mut [P],
    cp: &mut [S],
    mut extra: Option<&mut [S]>,
) -> Result<(), Error> {
    let n = diag.len();
    let mut c_prev = S::ZERO;
    let mut d_prev = P::zero();
    let mut z_prev = S::ZERO;
    for i in 0..n {
        let a = if i == 0 { S::ZERO } else { sub[i] };
        let b = if i == 0 {
            ends.0
        } else if i + 1 == n {
            ends.1
        } else {
            diag[i]
        };
        let c = if i + 1 == n { S::ZERO } else { sup[i] };
        let pivot = sub_(b, mul(a, c_prev)?)?;
        if pivot == S::ZERO {
            return Err(Error::InvalidArgument);
        }
        c_prev = div(c, pivot)?;
        cp[i] = c_prev;
        d_prev = p_div(p_sub_scaled(rhs[i], a, d_prev)?, pivot)?;
        rhs[i] = d_prev;
        if let Some(z) = extra.as_deref_mut() {
            z_prev = div(sub_(z[i], mul(a, z_prev)?)?, pivot)?;
            z[i] = z_prev;
        }
    }
    for i in (0..n - 1).rev() {
        rhs[i] = p_sub_scaled(rhs[i], cp[i], rhs[i + 1])?;
        if let Some(z) = extra.as_deref_mut() {
            z[i] = sub_(z[i], mul(cp[i], z[i + 1])?)?;
        }
    }
    Ok(())
}

fn mul<S: Scalar>(a: S, b: S) -> Result<S, Error> {
    if S::fits(a.to_f64() * b.to_f64()) {
        Ok(a * b)
    } else {
        Err(Error::OutOfRange)
    }
}

fn add<S: Scalar>(a: S, b: S) -> Result<S, Error> {
    if S::fits(a.to_f64() + b.to_f64()) {
        Ok(a + b)
    } else {
        Err(Error::OutOfRange)
    }
}

fn sub_<S: Scalar>(a: S, b: S) -> Result<S, Error> {
    if S::fits(a.to_f64() - b.to_f64()) {
        Ok(a - b)
    } else {
        Err(Error::OutOfRange)
    }
}

fn div<S: Scalar>(a: S, b: S) -> Result<S, Error> {
    if b == S::ZERO {
        return Err(Error::InvalidArgument);
    }
    if S::fits(a.to_f64() / b.to_f64()) {
        Ok(a / b)
    } else {
        Err(Error::OutOfRange)
    }
}

/// `p − s·q`, checked coordinate by coordinate.
fn p_sub_scaled<S: Scalar, P: Point<Scalar = S>>(p: P, s: S, q: P) -> Result<P, Error> {
    let mut result = Ok(());
    let out = P::from_coords(|i| {
        let step = mul(s, q.coord(i)).and_then(|sq| sub_(p.coord(i), sq));
        step.unwrap_or_else(|e| {
            result = Err(e);
            S::ZERO
        })
    });
    result.map(|()| out)
}

/// `p / s`, checked coordinate by coordinate.
fn p_div<S: Scalar, P: Point<Scalar = S>>(p: P, s: S) -> Result<P, Error> {
    if s == S::ZERO {
        return Err(Error::InvalidArgument);
    }
    let mut result = Ok(());
    let out = P::from_coords(|i| {
        let c = p.coord(i);
        if S::fits(c.to_f64() / s.to_f64()) {
            c / s
        } else {
            result = Err(Error::OutOfRange);
            S::ZERO
        }
    });
    result.map(|()| out)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::scalar::{I16F16, I32F32};

    /// `A·x` for the (cyclic when `cyclic`) tridiagonal matrix, in f64.
    fn matvec(sub: &[f64], diag: &[f64], sup: &[f64], x: &[f64], cyclic: bool) -> [f64; 8] {
        let n = diag.len();
        let mut out = [0.0; 8];
        for i in 0..n {
            let mut s = diag[i] * x[i];
            if i > 0 {
                s += sub[i] * x[i - 1];
            } else if cyclic {
                s += sub[0] * x[n - 1];
            }
            if i + 1 < n {
                s += sup[i] * x[i + 1];
            } else if cyclic {
                s += sup[n - 1] * x[0];
            }
            out[i] = s;
        }
        out
    }

    #[test]
    fn thomas_hand_solved_two_columns() {
        let sub = [0.0, 1.0, 1.0];
        let diag = [2.0, 2.0, 2.0];
        let sup = [1.0, 1.0, 0.0];
        // columns: x = (1, 2, 3) and x = (-1, 0, 1)
        let mut rhs = [[4.0_f64, -2.0], [8.0, 0.0], [8.0, 2.0]];
        let mut scratch = [0.0; 3];
        solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch).unwrap();
        let want = [[1.0, -1.0], [2.0, 0.0], [3.0, 1.0]];
        for (r, w) in rhs.iter().zip(want) {
            assert!(
                (r[0] - w[0]).abs() < 1e-15 && (r[1] - w[1]).abs() < 1e-15,
                "{r:?}"
            );
        }
    }

    #[test]
    fn thomas_nonsymmetric() {
        // [3 -1 0 0; 2 5 1 0; 0 -2 4 1; 0 0 1 2] x = ?  with x = (1, -2, 0.5, 4)
        let sub = [0.0, 2.0, -2.0, 1.0];
        let diag = [3.0, 5.0, 4.0, 2.0];
        let sup = [-1.0, 1.0, 1.0, 0.0];
        let x = [1.0, -2.0, 0.5, 4.0];
        let b = matvec(&sub, &diag, &sup, &x, false);
        // hand check of the right-hand side: 3+2=5, 2-10+0.5=-7.5, 4+2+4=10, 0.5+8=8.5
        assert_eq!(&b[..4], &[5.0, -7.5, 10.0, 8.5]);
        let mut rhs = [[b[0]], [b[1]], [b[2]], [b[3]]];
        let mut scratch = [0.0; 5];
        solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch).unwrap();
        for (r, want) in rhs.iter().zip(x) {
            assert!((r[0] - want).abs() < 1e-14, "{r:?} vs {want}");
        }
    }

    #[test]
    fn thomas_fixed_point() {
        let f = |v: f64| I32F32::from_num(v);
        let sub = [f(0.0), f(1.0), f(1.0)];
        let diag = [f(2.0), f(2.0), f(2.0)];
        let sup = [f(1.0), f(1.0), f(0.0)];
        let mut rhs = [[f(4.0)], [f(8.0)], [f(8.0)]];
        let mut scratch = [f(0.0); 3];
        solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch).unwrap();
        for (r, want) in rhs.iter().zip([1.0, 2.0, 3.0]) {
            assert!((r[0].to_num::<f64>() - want).abs() < 1e-8);
        }
        let g = |v: f64| I16F16::from_num(v);
        let mut rhs = [[g(4.0)], [g(8.0)], [g(8.0)]];
        let mut scratch = [g(0.0); 3];
        let (sub, diag, sup) = (
            sub.map(|x| g(x.to_num())),
            diag.map(|x| g(x.to_num())),
            sup.map(|x| g(x.to_num())),
        );
        solve_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut scratch).unwrap();
        for (r, want) in rhs.iter().zip([1.0, 2.0, 3.0]) {
            assert!((r[0].to_num::<f64>() - want).abs() < 1e-3);
        }
    }

    #[test]
    fn empty_and_single() {
        let mut rhs: [[f64; 1]; 0] = [];
        assert_eq!(solve_tridiagonal(&[], &[], &[], &mut rhs, &mut []), Ok(()));
        let mut rhs = [[6.0_f64]];
        solve_tridiagonal(&[9.0], &[3.0], &[9.0], &mut rhs, &mut [0.0]).unwrap();
        assert_eq!(rhs, [[2.0]]);
    }

    #[test]
    fn zero_pivot_is_invalid_argument() {
        let mut rhs = [[1.0_f64], [1.0]];
        assert_eq!(
            solve_tridiagonal(
                &[0.0, 1.0],
                &[0.0, 1.0],
                &[1.0, 0.0],
                &mut rhs,
                &mut [0.0; 2]
            ),
            Err(Error::InvalidArgument)
        );
        // second pivot: 1 - 1*1/1 = 0
        let mut rhs = [[1.0_f64], [1.0]];
        assert_eq!(
            solve_tridiagonal(
                &[0.0, 1.0],
                &[1.0, 1.0],
                &[1.0, 0.0],
                &mut rhs,
                &mut [0.0; 2]
            ),
            Err(Error::InvalidArgument)
        );
    }

    #[test]
    fn length_mismatch() {
        let mut rhs = [[1.0_f64], [1.0]];
        assert_eq!(
            solve_tridiagonal(&[0.0], &[1.0, 1.0], &[0.0, 0.0], &mut rhs, &mut [0.0; 2]),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 1
            })
        );
        assert_eq!(
            solve_tridiagonal(
                &[0.0, 0.0],
                &[1.0, 1.0],
                &[0.0, 0.0],
                &mut rhs,
                &mut [0.0; 1]
            ),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 1
            })
        );
        let mut rhs3 = [[1.0_f64]; 3];
        assert_eq!(
            solve_tridiagonal(
                &[0.0, 0.0],
                &[1.0, 1.0],
                &[0.0, 0.0],
                &mut rhs3,
                &mut [0.0; 3]
            ),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 3
            })
        );
        assert_eq!(
            solve_cyclic_tridiagonal(
                &[0.0, 0.0],
                &[1.0, 1.0],
                &[0.0, 0.0],
                &mut rhs,
                &mut [0.0; 2],
                &mut [0.0; 1]
            ),
            Err(Error::LengthMismatch {
                expected: 2,
                found: 1
            })
        );
    }

    #[test]
    fn non_finite_and_out_of_range() {
        let mut rhs = [[f64::NAN]];
        assert_eq!(
            solve_tridiagonal(&[0.0], &[1.0], &[0.0], &mut rhs, &mut [0.0]),
            Err(Error::NonFinite)
        );
        let tiny = I16F16::from_bits(1);
        let mut rhs = [[I16F16::from_num(100)]];
        assert_eq!(
            solve_tridiagonal(&[tiny], &[tiny], &[tiny], &mut rhs, &mut [tiny]),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn cyclic_symmetric() {
        let sub = [1.0, 1.0, 1.0, 1.0];
        let diag = [4.0, 4.0, 4.0, 4.0];
        let sup = [1.0, 1.0, 1.0, 1.0];
        let b = matvec(&sub, &diag, &sup, &[1.0, 2.0, 3.0, 4.0], true);
        assert_eq!(&b[..4], &[10.0, 12.0, 18.0, 20.0]);
        let mut rhs = [[10.0_f64, 1.0], [12.0, 1.0], [18.0, 1.0], [20.0, 1.0]];
        let (mut s, mut c) = ([0.0; 4], [0.0; 4]);
        solve_cyclic_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut s, &mut c).unwrap();
        for (r, want) in rhs.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((r[0] - want).abs() < 1e-14);
            // all-ones right-hand side: every row sums to 6
            assert!((r[1] - 1.0 / 6.0).abs() < 1e-15);
        }
    }

    #[test]
    fn cyclic_nonsymmetric_hand_solved() {
        // [3 1 0 2; 1 5 -1 0; 0 2 4 1; -1 0 1 6], x = (1, -1, 2, 0.5)
        let sub = [2.0, 1.0, 2.0, 1.0];
        let diag = [3.0, 5.0, 4.0, 6.0];
        let sup = [1.0, -1.0, 1.0, -1.0];
        let x = [1.0, -1.0, 2.0, 0.5];
        let b = matvec(&sub, &diag, &sup, &x, true);
        assert_eq!(&b[..4], &[3.0, -6.0, 6.5, 4.0]);
        let mut rhs = [[3.0_f64], [-6.0], [6.5], [4.0]];
        let (mut s, mut c) = ([0.0; 4], [0.0; 4]);
        solve_cyclic_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut s, &mut c).unwrap();
        for (r, want) in rhs.iter().zip(x) {
            assert!((r[0] - want).abs() < 1e-14, "{r:?} vs {want}");
        }
    }

    #[test]
    fn cyclic_small_sizes() {
        // n = 2: [4, 1+2; 3+1, 5] x = (1, 2) -> (10, 14)
        let mut rhs = [[10.0_f64], [14.0]];
        let (mut s, mut c) = ([0.0; 2], [0.0; 2]);
        solve_cyclic_tridiagonal(
            &[2.0, 3.0],
            &[4.0, 5.0],
            &[1.0, 1.0],
            &mut rhs,
            &mut s,
            &mut c,
        )
        .unwrap();
        assert!((rhs[0][0] - 1.0).abs() < 1e-14 && (rhs[1][0] - 2.0).abs() < 1e-14);
        // n = 1: (1 + 2 + 3) x = 12
        let mut rhs = [[12.0_f64]];
        solve_cyclic_tridiagonal(&[1.0], &[2.0], &[3.0], &mut rhs, &mut [0.0], &mut [0.0]).unwrap();
        assert_eq!(rhs, [[2.0]]);
    }

    #[test]
    fn cyclic_fixed_point() {
        let f = |v: f64| I32F32::from_num(v);
        let sub = [1.0, 1.0, 1.0, 1.0].map(f);
        let diag = [4.0, 4.0, 4.0, 4.0].map(f);
        let sup = [1.0, 1.0, 1.0, 1.0].map(f);
        let mut rhs = [[10.0], [12.0], [18.0], [20.0]].map(|[v]| [f(v)]);
        let (mut s, mut c) = ([f(0.0); 4], [f(0.0); 4]);
        solve_cyclic_tridiagonal(&sub, &diag, &sup, &mut rhs, &mut s, &mut c).unwrap();
        for (r, want) in rhs.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((r[0].to_num::<f64>() - want).abs() < 1e-8);
        }
    }

    #[test]
    fn cyclic_singular() {
        // diag[0] = 0 (γ = 0)
        let mut rhs = [[1.0_f64], [1.0], [1.0]];
        assert_eq!(
            solve_cyclic_tridiagonal(
                &[1.0; 3],
                &[0.0, 1.0, 1.0],
                &[1.0; 3],
                &mut rhs,
                &mut [0.0; 3],
                &mut [0.0; 3]
            ),
            Err(Error::InvalidArgument)
        );
        // all-ones 3x3 circulant [1 1 1; 1 1 1; 1 1 1] is singular
        let mut rhs = [[1.0_f64], [1.0], [1.0]];
        assert_eq!(
            solve_cyclic_tridiagonal(
                &[1.0; 3],
                &[1.0; 3],
                &[1.0; 3],
                &mut rhs,
                &mut [0.0; 3],
                &mut [0.0; 3]
            ),
            Err(Error::InvalidArgument)
        );
    }
}
