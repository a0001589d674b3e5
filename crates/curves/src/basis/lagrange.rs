//! The Lagrange basis of a node vector (Farin, *Curves and Surfaces for CAGD*, 5th ed., §6.2
//! "Lagrange Polynomials"; Burden & Faires, *Numerical Analysis*, §3.1).
//!
//! For nodes `u_0 < u_1 < … < u_g`,
//! `L_i^g(t) = Π_{k≠i} (t − u_k)/(u_i − u_k)`: `L_i^g(u_i) = 1` and `L_i^g(u_j) = 0` for
//! `j ≠ i`, so `c(t) = Σ q_i L_i^g(t)` interpolates the points `q_i` at the nodes.

use crate::error::Error;
use crate::scalar::Scalar;

/// A validated node vector `u_0 < u_1 < … < u_g` (`g = N − 1`) and its Lagrange basis
/// `L_i^g(t) = Π_{k≠i} (t − u_k)/(u_i − u_k)` (the product formula).
///
/// The parameter `t` is clamped to `[u_0, u_g]`. Each value is the product of the `g` ratios
/// `(t − u_k)/(u_i − u_k)`, one division per factor (the divisors are non-zero because the
/// nodes are strictly increasing in the scalar type).
///
/// # Fixed-point range
/// The constructor checks that every node fits and that, for every `i`, the bound
/// `Π_{k≠i} max(1, max(|u_0 − u_k|, |u_g − u_k|) / |u_i − u_k|)` on all partial products
/// fits; otherwise [`Error::OutOfRange`].
///
/// ```
/// use strak_curves::basis::LagrangeBasis;
///
/// // Nodes {0, 1, 3}: L_0 = (t² − 4t + 3)/3, L_1 = t(t − 3)/−2, L_2 = t(t − 1)/6
/// let l = LagrangeBasis::new([0.0, 1.0, 3.0])?;
/// assert_eq!(l.values(2.0), [-1.0 / 3.0, 1.0, 1.0 / 3.0]);
/// # Ok::<(), strak_curves::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LagrangeBasis<S: Scalar, const N: usize> {
    nodes: [S; N],
}

impl<S: Scalar, const N: usize> LagrangeBasis<S, N> {
    /// The Lagrange basis of the nodes `[u_0, …, u_g]`.
    ///
    /// # Errors
    /// [`Error::TooFewPoints`] for `N = 0`, [`Error::NonFinite`] for a NaN/∞ node,
    /// [`Error::NodesNotIncreasing`] when `u_i ≤ u_{i−1}`, [`Error::OutOfRange`] when a node or
    /// a basis value could leave the scalar's range.
    ///
    /// ```
    /// use strak_curves::{Error, basis::LagrangeBasis};
    /// assert!(LagrangeBasis::new([0.0_f32, 0.5, 1.0]).is_ok());
    /// assert_eq!(
    ///     LagrangeBasis::new([0.0, 1.0, 1.0]),
    ///     Err(Error::NodesNotIncreasing { index: 2 })
    /// );
    /// ```
    pub fn new(nodes: [S; N]) -> Result<Self, Error> {
        if N == 0 {
            return Err(Error::TooFewPoints {
                required: 1,
                found: 0,
            });
        }
        if !nodes.iter().all(|u| u.is_finite()) {
            return Err(Error::NonFinite);
        }
        for (index, w) in nodes.windows(2).enumerate() {
            if w[1] <= w[0] {
                return Err(Error::NodesNotIncreasing { index: index + 1 });
            }
        }
        if !nodes.iter().all(|u| S::fits(u.to_f64())) {
            return Err(Error::OutOfRange);
        }
        let first = nodes.first().map_or(0.0, |u| u.to_f64());
        let last = nodes.last().map_or(0.0, |u| u.to_f64());
        for (i, ui) in nodes.iter().enumerate() {
            let mut bound = 1.0_f64;
            for (k, uk) in nodes.iter().enumerate() {
                if k != i {
                    let uk = uk.to_f64();
                    let span = (first - uk).abs().max((last - uk).abs());
                    bound *= (span / (ui.to_f64() - uk).abs()).max(1.0);
                }
            }
            if !S::fits(bound) {
                return Err(Error::OutOfRange);
            }
        }
        Ok(Self { nodes })
    }

    /// The nodes `[u_0, …, u_g]`.
    pub fn nodes(&self) -> &[S; N] {
        &self.nodes
    }

    /// The degree `g = N − 1`.
    pub fn degree(&self) -> usize {
        N.saturating_sub(1)
    }

    /// The interval `[u_0, u_g]` to which parameters are clamped.
    pub fn domain(&self) -> (S, S) {
        let first = self.nodes.first().copied().unwrap_or(S::ZERO);
        let last = self.nodes.last().copied().unwrap_or(S::ZERO);
        (first, last)
    }

    /// `L_i^g(t)` by the product formula, `t` clamped to `[u_0, u_g]`; zero for `i ≥ N`.
    ///
    /// ```
    /// use strak_curves::basis::LagrangeBasis;
    /// let l = LagrangeBasis::new([0.0, 1.0, 3.0])?;
    /// assert_eq!(l.value(0, 1.0), 0.0);
    /// assert_eq!(l.value(1, 1.0), 1.0);
    /// # Ok::<(), strak_curves::Error>(())
    /// ```
    pub fn value(&self, i: usize, t: S) -> S {
        let Some(&ui) = self.nodes.get(i) else {
            return S::ZERO;
        };
        let (lo, hi) = self.domain();
        let t = t.clamp_to(lo, hi);
        let mut l = S::ONE;
        for (k, &uk) in self.nodes.iter().enumerate() {
            if k != i {
                l *= (t - uk) / (ui - uk);
            }
        }
        l
    }

    /// All values `[L_0^g(t), …, L_g^g(t)]`, `t` clamped to `[u_0, u_g]`. They sum to one
    /// (so Lagrange curves are affinely invariant) but may be negative (no convex hull
    /// property).
    pub fn values(&self, t: S) -> [S; N] {
        core::array::from_fn(|i| self.value(i, t))
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    fn worked_basis(t: f64) -> [f64; 3] {
        [
            (t * t - 4.0 * t + 3.0) / 3.0,
            t * (t - 3.0) / -2.0,
            t * (t - 1.0) / 6.0,
        ]
    }

    #[test]
    fn worked_example_nodes_0_1_3() {
        let l = LagrangeBasis::new([0.0, 1.0, 3.0]).unwrap();
        assert_eq!(l.degree(), 2);
        assert_eq!(l.domain(), (0.0, 3.0));
        for step in 0..=12 {
            let t = step as f64 / 4.0;
            let v = l.values(t);
            let s = worked_basis(t);
            for i in 0..3 {
                assert!((v[i] - s[i]).abs() < 1e-15, "i={i} t={t}");
            }
            assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
        // Kronecker property at the nodes, exactly
        assert_eq!(l.values(0.0), [1.0, 0.0, 0.0]);
        assert_eq!(l.values(1.0), [0.0, 1.0, 0.0]);
        assert_eq!(l.values(3.0), [0.0, 0.0, 1.0]);
        assert_eq!(l.value(3, 1.0), 0.0);
        // clamped
        assert_eq!(l.values(-5.0), l.values(0.0));
        assert_eq!(l.values(9.0), l.values(3.0));
    }

    #[test]
    fn worked_example_curve_through_the_points() {
        // q = (1, 0), (−1, 0), (3, 3) at u = 0, 1, 3.
        let l = LagrangeBasis::new([0.0, 1.0, 3.0]).unwrap();
        let q = [[1.0, 0.0], [-1.0, 0.0], [3.0, 3.0]];
        let c = |t: f64| {
            let v = l.values(t);
            let mut p = [0.0; 2];
            for i in 0..3 {
                p[0] += q[i][0] * v[i];
                p[1] += q[i][1] * v[i];
            }
            p
        };
        assert_eq!(c(0.0), [1.0, 0.0]);
        assert_eq!(c(1.0), [-1.0, 0.0]);
        assert_eq!(c(3.0), [3.0, 3.0]);
        let c2 = c(2.0);
        assert!((c2[0] + 1.0 / 3.0).abs() < 1e-15 && (c2[1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn single_node_is_constant_one() {
        let l = LagrangeBasis::new([2.0]).unwrap();
        assert_eq!(l.values(7.0), [1.0]);
        assert_eq!(l.degree(), 0);
    }

    #[test]
    fn error_too_few_points() {
        assert_eq!(
            LagrangeBasis::<f64, 0>::new([]),
            Err(Error::TooFewPoints {
                required: 1,
                found: 0
            })
        );
    }

    #[test]
    fn error_non_finite() {
        assert_eq!(
            LagrangeBasis::new([0.0, f64::NAN, 1.0]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            LagrangeBasis::new([0.0_f32, f32::INFINITY]),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn error_nodes_not_increasing() {
        assert_eq!(
            LagrangeBasis::new([0.0, 2.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        assert_eq!(
            LagrangeBasis::new([0.0, 0.0]),
            Err(Error::NodesNotIncreasing { index: 1 })
        );
    }

    #[test]
    fn error_out_of_range() {
        // close nodes far apart from the rest: the ratios explode in I16F16
        let n = [0.0, 0.001, 0.002, 100.0].map(I16F16::from_num);
        assert_eq!(LagrangeBasis::new(n), Err(Error::OutOfRange));
        let n = [0.0, 20000.0].map(I16F16::from_num);
        assert_eq!(LagrangeBasis::new(n), Err(Error::OutOfRange));
        // the same nodes are fine in f64
        assert!(LagrangeBasis::new([0.0, 0.001, 0.002, 100.0]).is_ok());
    }

    #[test]
    fn f32_and_fixed_point_agree_with_f64() {
        let lf = LagrangeBasis::new([0.0, 1.0, 3.0]).unwrap();
        let l32 = LagrangeBasis::new([0.0_f32, 1.0, 3.0]).unwrap();
        let lx = LagrangeBasis::new([0.0, 1.0, 3.0].map(I16F16::from_num)).unwrap();
        let ly = LagrangeBasis::new([0.0, 1.0, 3.0].map(I32F32::from_num)).unwrap();
        for step in 0..=24 {
            let t = step as f64 / 8.0;
            let r = lf.values(t);
            let a = l32.values(t as f32);
            let x = lx.values(I16F16::from_num(t));
            let y = ly.values(I32F32::from_num(t));
            for i in 0..3 {
                assert!((f64::from(a[i]) - r[i]).abs() < 1e-6);
                assert!((x[i].to_f64() - r[i]).abs() < 8.0 * <I16F16 as Scalar>::EPSILON);
                assert!((y[i].to_f64() - r[i]).abs() < 8.0 * <I32F32 as Scalar>::EPSILON);
            }
        }
    }
}
