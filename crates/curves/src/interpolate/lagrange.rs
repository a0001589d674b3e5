//! Lagrange curves: the polynomial curve of degree `n` through `n + 1` points `q_i` at nodes
//! `u_i` (Farin, *Curves and Surfaces for CAGD*, 5th ed., §6.2 "Lagrange Polynomials"),
//! `c(t) = Σ q_i·L_i^n(t)` with `L_i^n(t) = Π_{k≠i} (t − u_k)/(u_i − u_k)`.
//!
//! Points are evaluated with Neville's algorithm (Burden & Faires, *Numerical Analysis*,
//! §3.2; Aitken's algorithm in Farin §6.1): the interpolant of nodes `i..=j` is the affine
//! combination `(1 − λ)·p_{i..j−1} + λ·p_{i+1..j}` with `λ = (t − u_i)/(u_j − u_i)`, the
//! analogue of de Casteljau's scheme. Derivatives use the Newton form
//! `c(t) = Σ [u_0..u_i]q · Π_{m<i}(t − u_m)` (divided differences, computed once at
//! construction; de Boor, *A Practical Guide to Splines*, ch. I) and the Horner scheme for
//! derivatives. Many nodes make the curve oscillate (Runge's example: de Boor ch. II; Farin
//! §6.4 "Limits of Lagrange Interpolation"); prefer splines for more than a handful of points.

use heapless::Vec;

use super::hermite::check_points;
use super::parameterization::NodeSource;
use crate::curve::{ParamCurve, ParamCurveDeriv, PieceDeriv};
use crate::error::Error;
use crate::point::{MAX_DIM, Point};
use crate::scalar::Scalar;

/// The Lagrange (interpolating polynomial) curve through at most `N` points, degree
/// `n = points − 1`, domain `[u_0, u_n]` (parameters outside are clamped).
///
/// ```
/// use strak_curves::{LagrangeCurve, ParamCurve, ParamCurveDeriv};
///
/// // Nodes {0, 1, 3}, points (1,0), (−1,0), (3,3):
/// // c(t) = ((4t² − 10t + 3)/3, t(t − 1)/2)
/// let c = LagrangeCurve::<_, 4>::new(&[[1.0_f64, 0.0], [-1.0, 0.0], [3.0, 3.0]], &[0.0, 1.0, 3.0])
///     .unwrap();
/// assert_eq!(c.eval(1.0), [-1.0, 0.0]);
/// let p = c.eval(2.0);
/// assert!((p[0] + 1.0 / 3.0).abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15);
/// let a = c.deriv(2.0, 2);
/// assert!((a[0] - 8.0 / 3.0).abs() < 1e-14 && (a[1] - 1.0).abs() < 1e-14);
/// assert_eq!(c.deriv(2.0, 3), [0.0, 0.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct LagrangeCurve<P: Point, const N: usize> {
    nodes: Vec<P::Scalar, N>,
    points: Vec<P, N>,
    /// Newton coefficients: the divided differences `[u_0, …, u_i] q`.
    newton: Vec<P, N>,
}

impl<P: Point, const N: usize> LagrangeCurve<P, N> {
    /// The Lagrange curve through `points` at the given nodes or at nodes computed by a
    /// [`Parameterization`](crate::Parameterization).
    ///
    /// The divided differences are computed in `f64` and rounded once to the scalar type.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] below 2 points, [`Error::CapacityExceeded`] above `N`,
    /// [`Error::LengthMismatch`] (given nodes), [`Error::NonFinite`],
    /// [`Error::NodesNotIncreasing`], [`Error::ZeroLengthInterval`] (computed nodes),
    /// [`Error::OutOfRange`] when a bound on the values an evaluation can produce (Neville's
    /// intermediate interpolants and weights, Newton coefficients, derivatives of every
    /// order) does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Error, LagrangeCurve, Parameterization};
    ///
    /// let pts = [[0.0_f32], [1.0], [4.0]];
    /// let c = LagrangeCurve::<_, 4>::new(&pts, Parameterization::Uniform).unwrap();
    /// assert_eq!(c.nodes(), &[0.0, 1.0, 2.0]);
    /// assert_eq!(
    ///     LagrangeCurve::<_, 2>::new(&pts, Parameterization::Uniform),
    ///     Err(Error::CapacityExceeded { capacity: 2, required: 3 })
    /// );
    /// ```
    pub fn new<'a>(
        points: &[P],
        nodes: impl Into<NodeSource<'a, P::Scalar>>,
    ) -> Result<Self, Error> {
        check_points::<P, N>(points, 2)?;
        let nodes = nodes.into().resolve::<P, N>(points)?;
        // The derivative order k (≤ n) is counted in the scalar type.
        #[allow(clippy::cast_precision_loss)]
        if !<P::Scalar as Scalar>::fits(points.len() as f64) {
            return Err(Error::OutOfRange);
        }
        let n = points.len() - 1;
        let mut u = [0.0_f64; N];
        for (x, node) in u.iter_mut().zip(nodes.iter()) {
            *x = node.to_f64();
        }
        let mut coef = [[0.0_f64; MAX_DIM]; N];
        for (c, p) in coef.iter_mut().zip(points.iter()) {
            *c = p.to_f64_array();
        }
        // Divided differences, in place: coef[i] = [u_{i−w} … u_i] q after step w.
        for w in 1..=n {
            for i in (w..=n).rev() {
                let du = u[i] - u[i - w];
                let prev = coef[i - 1];
                for (c, p) in coef[i].iter_mut().zip(prev.iter()) {
                    *c = (*c - p) / du;
                }
            }
        }
        let mut newton: Vec<P, N> = Vec::new();
        for c in coef.iter().take(n + 1) {
            let p = P::from_f64_slice(&c[..P::DIM]).ok_or(Error::OutOfRange)?;
            newton.push(p).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: points.len(),
            })?;
        }
        let mut q = [0.0_f64; N];
        for (m, p) in q.iter_mut().zip(points.iter()) {
            *m = p.max_abs();
        }
        let mut c = [0.0_f64; N];
        for (m, p) in c.iter_mut().zip(newton.iter()) {
            *m = p.max_abs();
        }
        let bound = worst(
            neville_bound::<N>(&u[..=n], &q[..=n]),
            newton_bound(&u[..=n], &c[..=n]),
        );
        if !<P::Scalar as Scalar>::fits(bound) {
            return Err(Error::OutOfRange);
        }
        Ok(Self {
            nodes,
            points: Vec::from_slice(points).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: points.len(),
            })?,
            newton,
        })
    }

    /// The nodes `u_0 < … < u_n`.
    pub fn nodes(&self) -> &[P::Scalar] {
        &self.nodes
    }

    /// The interpolated points `q_0 … q_n`.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The coefficients of the Newton form: the divided differences `[u_0, …, u_i] q`.
    pub fn newton_coefficients(&self) -> &[P] {
        &self.newton
    }

    /// The polynomial degree `n` (number of points − 1).
    pub fn degree(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// Neville's algorithm at `u` (already clamped).
    fn neville(&self, u: P::Scalar) -> P {
        let mut p = [P::zero(); N];
        for (d, s) in p.iter_mut().zip(self.points.iter()) {
            *d = *s;
        }
        let n = self.degree();
        for w in 1..=n {
            for i in 0..=(n - w) {
                let (Some(&ui), Some(&uj), Some(&b)) =
                    (self.nodes.get(i), self.nodes.get(i + w), p.get(i + 1))
                else {
                    continue;
                };
                let lambda = (u - ui) / (uj - ui);
                if let Some(a) = p.get_mut(i) {
                    *a = a.lerp(b, lambda);
                }
            }
        }
        p.first().copied().unwrap_or_else(P::zero)
    }

    /// The `k`-th derivative (`1 ≤ k ≤ n`) at `u` (already clamped) by Horner's scheme for
    /// the Newton form, carrying the Taylor coefficients `d_j = c^{(j)}/j!`.
    fn newton_deriv(&self, u: P::Scalar, k: usize) -> P {
        let n = self.degree();
        let mut d = [P::zero(); N];
        if let (Some(first), Some(&top)) = (d.first_mut(), self.newton.get(n)) {
            *first = top;
        }
        for i in (0..n).rev() {
            let (Some(&ui), Some(&ci)) = (self.nodes.get(i), self.newton.get(i)) else {
                continue;
            };
            let x = u - ui;
            for j in (1..=k).rev() {
                let lower = d.get(j - 1).copied().unwrap_or_else(P::zero);
                if let Some(slot) = d.get_mut(j) {
                    *slot = slot.times(x).plus(lower);
                }
            }
            if let Some(d0) = d.first_mut() {
                *d0 = d0.times(x).plus(ci);
            }
        }
        let mut r = d.get(k).copied().unwrap_or_else(P::zero);
        let mut f = P::Scalar::ONE;
        for _ in 2..=k {
            f += P::Scalar::ONE;
            r = r.times(f);
        }
        r
    }
}

/// `max(a, b)` that treats NaN as unbounded.
fn worst(a: f64, b: f64) -> f64 {
    if b.is_nan() { f64::INFINITY } else { a.max(b) }
}

/// Bound on Neville's intermediate values over the domain: for nodes `i..=j`, the interpolant
/// is at most `B_ij = Σ_l |q_l|·Π_{m≠l} a_m/|u_l − u_m|` with `a_m = max |t − u_m|` (a bound
/// on the Lagrange basis of those nodes); the weights satisfy `|λ| ≤ a_i/(u_j − u_i)` and
/// `|1 − λ| ≤ a_j/(u_j − u_i)`, so each step's products are at most
/// `|1 − λ|·B_{i,j−1} + |λ|·B_{i+1,j}`. `O(n³)` time, `O(N)` storage.
fn neville_bound<const N: usize>(u: &[f64], q: &[f64]) -> f64 {
    let (Some(&u0), Some(&un)) = (u.first(), u.last()) else {
        return 0.0;
    };
    let n = u.len() - 1;
    let mut a = [0.0_f64; N];
    for (am, &x) in a.iter_mut().zip(u.iter()) {
        *am = (x - u0).max(un - x);
    }
    let mut bound = un - u0;
    for &x in q {
        bound = worst(bound, x);
    }
    // prev[j] = B_{i+1, j}, cur[j] = B_{i, j}, w[l] = the product for point l.
    let mut prev = [0.0_f64; N];
    let mut cur = [0.0_f64; N];
    let mut w = [0.0_f64; N];
    for i in (0..=n).rev() {
        cur[i] = q[i];
        w[i] = 1.0;
        for j in i + 1..=n {
            let mut wj = 1.0;
            for l in i..j {
                let dist = (u[l] - u[j]).abs();
                w[l] *= a[j] / dist;
                wj *= a[l] / dist;
            }
            w[j] = wj;
            let b: f64 = (i..=j).map(|l| q[l] * w[l]).sum();
            cur[j] = b;
            let span = u[j] - u[i];
            let (lam, one_minus) = (a[i] / span, a[j] / span);
            let prod = one_minus * cur[j - 1] + lam * prev[j];
            for v in [b, lam, one_minus, prod] {
                bound = worst(bound, v);
            }
        }
        prev = cur;
    }
    bound
}

/// Bound on the Horner scheme for derivatives of the Newton form: after processing node `i`
/// the accumulator `d_j` (the `j`-th derivative over `j!` of `Σ_{l≥i} c_l Π_{m=i}^{l−1}(t − u_m)`)
/// is at most `Σ_{l≥i} |c_l|·C(l − i, j)·A^{l−i−j}` with `A = u_n − u_0`; the final
/// multiplication by `k!` gives the factor `j!`. `O(n³)`.
fn newton_bound(u: &[f64], c: &[f64]) -> f64 {
    let (Some(&u0), Some(&un)) = (u.first(), u.last()) else {
        return 0.0;
    };
    let n = u.len() - 1;
    let big_a = un - u0;
    let mut bound = 0.0_f64;
    for i in 0..=n {
        let mut fact = 1.0_f64;
        for j in 0..=(n - i) {
            if j > 0 {
                #[allow(clippy::cast_precision_loss)]
                let jf = j as f64;
                fact *= jf;
            }
            // F(r) = C(r, j)·A^{r−j}, r = l − i, starting at r = j.
            let mut f = 1.0_f64;
            let mut sum = 0.0_f64;
            for (r, &cl) in (j..).zip(c.iter().skip(i + j)) {
                sum += cl * f;
                #[allow(clippy::cast_precision_loss)]
                let (r1, k1) = ((r + 1) as f64, (r + 1 - j) as f64);
                f *= big_a * r1 / k1;
            }
            bound = worst(bound, sum * fact);
        }
    }
    bound
}

impl<P: Point, const N: usize> ParamCurve for LagrangeCurve<P, N> {
    type Point = P;

    fn domain(&self) -> (P::Scalar, P::Scalar) {
        let first = self.nodes.first().copied().unwrap_or(P::Scalar::ZERO);
        let last = self.nodes.last().copied().unwrap_or(P::Scalar::ONE);
        (first, last)
    }

    fn eval(&self, u: P::Scalar) -> P {
        let (a, b) = self.domain();
        self.neville(u.clamp_to(a, b))
    }
}

impl<P: Point, const N: usize> ParamCurveDeriv for LagrangeCurve<P, N> {
    fn deriv(&self, u: P::Scalar, k: usize) -> P {
        let (a, b) = self.domain();
        let u = u.clamp_to(a, b);
        if k == 0 {
            self.neville(u)
        } else if k > self.degree() {
            P::zero()
        } else {
            self.newton_deriv(u, k)
        }
    }
}

/// A single piece: [`PieceDeriv::piece_deriv`] is [`ParamCurveDeriv::deriv`].
impl<P: Point, const N: usize> PieceDeriv for LagrangeCurve<P, N> {
    fn piece_deriv(&self, _piece: usize, u: P::Scalar, k: usize) -> P {
        self.deriv(u, k)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::Parameterization;
    use crate::scalar::{I16F16, I32F32};

    const WORKED_PTS: [[f64; 2]; 3] = [[1.0, 0.0], [-1.0, 0.0], [3.0, 3.0]];
    const WORKED_U: [f64; 3] = [0.0, 1.0, 3.0];

    /// Expanded: c(t) = (1,0)(t² − 4t + 3)/3 + (−1,0)·t(t − 3)/(−2) + (3,3)·t(t − 1)/6.
    fn expanded(t: f64) -> [f64; 2] {
        let l0 = (t * t - 4.0 * t + 3.0) / 3.0;
        let l1 = t * (t - 3.0) / -2.0;
        let l2 = t * (t - 1.0) / 6.0;
        [1.0 * l0 - 1.0 * l1 + 3.0 * l2, 3.0 * l2]
    }

    fn near(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    fn curve() -> LagrangeCurve<[f64; 2], 4> {
        LagrangeCurve::new(&WORKED_PTS, &WORKED_U).unwrap()
    }

    #[test]
    fn worked_example() {
        let c = curve();
        assert_eq!(c.domain(), (0.0, 3.0));
        assert_eq!(c.degree(), 2);
        for j in 0..=30 {
            let t = f64::from(j) / 10.0;
            assert!(near(c.eval(t), expanded(t), 1e-14), "t = {t}");
        }
        for i in 0..3 {
            assert_eq!(c.eval(WORKED_U[i]), WORKED_PTS[i]);
        }
    }

    #[test]
    fn worked_example_derivatives() {
        // x = (4t² − 10t + 3)/3, y = t(t − 1)/2
        let c = curve();
        for j in 0..=30 {
            let t = f64::from(j) / 10.0;
            assert!(near(
                c.deriv(t, 1),
                [(8.0 * t - 10.0) / 3.0, t - 0.5],
                1e-14
            ));
            assert!(near(c.deriv(t, 2), [8.0 / 3.0, 1.0], 1e-14));
            assert_eq!(c.deriv(t, 3), [0.0, 0.0]);
            assert_eq!(c.deriv(t, 7), [0.0, 0.0]);
        }
        // Newton coefficients: q0, [u0,u1]q, [u0,u1,u2]q
        let nc = c.newton_coefficients();
        assert_eq!(nc[0], [1.0, 0.0]);
        assert_eq!(nc[1], [-2.0, 0.0]);
        assert!(near(nc[2], [4.0 / 3.0, 0.5], 1e-15));
    }

    #[test]
    fn clamps_parameter() {
        let c = curve();
        assert_eq!(c.eval(-1.0), WORKED_PTS[0]);
        assert_eq!(c.eval(4.0), WORKED_PTS[2]);
        assert_eq!(c.deriv(-1.0, 1), c.deriv(0.0, 1));
    }

    #[test]
    fn reproduces_cubic_and_its_derivatives() {
        // p(t) = t³ − 2t + 1 sampled at 4 uneven nodes, degree 3: exact reproduction.
        let p = |t: f64| t * t * t - 2.0 * t + 1.0;
        let u = [-1.0, 0.5, 1.0, 2.5];
        let pts = u.map(|t| [p(t)]);
        let c = LagrangeCurve::<_, 6>::new(&pts, &u).unwrap();
        for j in 0..=35 {
            let t = -1.0 + f64::from(j) / 10.0;
            assert!((c.eval(t)[0] - p(t)).abs() < 1e-13);
            assert!((c.deriv(t, 1)[0] - (3.0 * t * t - 2.0)).abs() < 1e-13);
            assert!((c.deriv(t, 2)[0] - 6.0 * t).abs() < 1e-12);
            assert!((c.deriv(t, 3)[0] - 6.0).abs() < 1e-12);
            assert_eq!(c.deriv(t, 4), [0.0]);
        }
    }

    #[test]
    fn parameterized_nodes() {
        let c = LagrangeCurve::<_, 4>::new(&WORKED_PTS, Parameterization::Uniform).unwrap();
        assert_eq!(c.nodes(), &[0.0, 1.0, 2.0]);
        assert_eq!(c.points(), &WORKED_PTS);
        assert_eq!(c.eval(2.0), WORKED_PTS[2]);
    }

    #[test]
    fn fixed_point_and_f32_match_f64() {
        let c = curve();
        let p16 = WORKED_PTS.map(|p| p.map(I16F16::from_num));
        let u16 = WORKED_U.map(I16F16::from_num);
        let p32 = WORKED_PTS.map(|p| p.map(I32F32::from_num));
        let u32_ = WORKED_U.map(I32F32::from_num);
        let pf = WORKED_PTS.map(|p| p.map(|x| x as f32));
        let uf = WORKED_U.map(|x| x as f32);
        let a = LagrangeCurve::<_, 4>::new(&p16, &u16).unwrap();
        let b = LagrangeCurve::<_, 4>::new(&p32, &u32_).unwrap();
        let f = LagrangeCurve::<_, 4>::new(&pf, &uf).unwrap();
        for j in 0..=30 {
            let t = f64::from(j) / 10.0;
            for k in 0..=2 {
                let want = c.deriv(t, k);
                let x = a.deriv(I16F16::from_num(t), k).map(|v| v.to_num::<f64>());
                let y = b.deriv(I32F32::from_num(t), k).map(|v| v.to_num::<f64>());
                let z = f.deriv(t as f32, k).map(f64::from);
                assert!(near(x, want, 5e-4), "I16F16 t={t} k={k}: {x:?} vs {want:?}");
                assert!(near(y, want, 1e-8), "I32F32 t={t} k={k}: {y:?} vs {want:?}");
                assert!(near(z, want, 1e-5), "f32 t={t} k={k}: {z:?} vs {want:?}");
            }
        }
    }

    #[test]
    fn errors() {
        let uni = Parameterization::Uniform;
        assert_eq!(
            LagrangeCurve::<_, 4>::new(&WORKED_PTS[..1], uni),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        assert_eq!(
            LagrangeCurve::<_, 2>::new(&WORKED_PTS, uni),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
        assert_eq!(
            LagrangeCurve::<_, 4>::new(&WORKED_PTS, &WORKED_U[..2]),
            Err(Error::LengthMismatch {
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            LagrangeCurve::<_, 4>::new(&[[0.0, 1.0], [f64::NAN, 0.0]], uni),
            Err(Error::NonFinite)
        );
        assert_eq!(
            LagrangeCurve::<_, 4>::new(&WORKED_PTS, &[0.0, 3.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        assert_eq!(
            LagrangeCurve::<_, 4>::new(&[[0.0], [1.0], [1.0]], Parameterization::ChordLength),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
        // I16F16: slope 100 / 2^-12 = 409 600 does not fit.
        let f = |x: f64| I16F16::from_num(x);
        assert_eq!(
            LagrangeCurve::<_, 4>::new(
                &[[f(0.0)], [f(100.0)], [f(0.0)]],
                &[f(0.0), f(1.0 / 4096.0), f(16.0)]
            ),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn bounds_cover_actual_values() {
        // The bounds are at least the values actually produced over the domain.
        let u = [0.0, 0.3, 1.0, 1.2, 2.0];
        let q = [1.0, -2.0, 0.5, 3.0, -1.0];
        let c = LagrangeCurve::<_, 5>::new(&q.map(|x| [x]), &u).unwrap();
        let mut cs = [0.0; 5];
        for (m, p) in cs.iter_mut().zip(c.newton_coefficients()) {
            *m = p[0].abs();
        }
        let nb = neville_bound::<5>(&u, &q.map(f64::abs));
        let db = newton_bound(&u, &cs);
        for j in 0..=200 {
            let t = 2.0 * f64::from(j) / 200.0;
            assert!(c.eval(t)[0].abs() <= nb);
            for k in 1..=4 {
                assert!(c.deriv(t, k)[0].abs() <= db, "k={k} t={t}");
            }
        }
    }
}
