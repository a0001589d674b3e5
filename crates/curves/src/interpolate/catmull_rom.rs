//! Catmull-Rom and cardinal splines: [`HermiteSpline`]s whose tangents are computed from the
//! neighbouring points (finite differences over the nodes; Catmull & Rom, "A class of local
//! interpolating splines", in Barnhill & Riesenfeld (eds.), *Computer Aided Geometric
//! Design*, Academic Press 1974). Each point influences the four pieces around it (local
//! control), and the curve is C¹.

use heapless::Vec;

use super::hermite::{HermiteSpline, check_points};
use super::parameterization::NodeSource;
use crate::error::Error;
use crate::point::{MAX_DIM, Point};
use crate::scalar::Scalar;

impl<P: Point, const N: usize> HermiteSpline<P, N> {
    /// The Catmull-Rom spline through `points`: the Hermite spline with tangents
    ///
    /// - `m_i = (q_{i+1} − q_{i−1}) / (u_{i+1} − u_{i−1})` at inner nodes (central difference),
    /// - `m_0 = (q_1 − q_0)/(u_1 − u_0)` and `m_n = (q_n − q_{n−1})/(u_n − u_{n−1})` at the ends
    ///   (one-sided differences).
    ///
    /// The tangents are computed in `f64` and rounded once to the scalar type. With two points
    /// the curve is the straight segment. The nodes are given, or computed by a
    /// [`Parameterization`](crate::Parameterization) (the caller picks the default).
    ///
    /// # Errors
    /// As [`HermiteSpline::new`]: [`Error::TooFewPoints`] (below 2), [`Error::CapacityExceeded`],
    /// [`Error::LengthMismatch`] (given nodes), [`Error::NonFinite`],
    /// [`Error::NodesNotIncreasing`], [`Error::ZeroLengthInterval`], [`Error::OutOfRange`].
    ///
    /// ```
    /// use strak_curves::{HermiteSpline, ParamCurve, ParamCurveDeriv, Parameterization};
    ///
    /// let pts = [[0.0_f64, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]];
    /// let c = HermiteSpline::<_, 8>::catmull_rom(&pts, Parameterization::Uniform).unwrap();
    /// assert_eq!(c.tangents()[1], [1.0, 0.0]); // (q2 − q0) / 2
    /// assert_eq!(c.tangents()[0], [1.0, 1.0]); // q1 − q0
    /// assert_eq!(c.eval(2.0), [2.0, 0.0]);
    /// assert_eq!(c.deriv(2.0, 1), [1.0, 0.0]);
    /// ```
    pub fn catmull_rom<'a>(
        points: &[P],
        params: impl Into<NodeSource<'a, P::Scalar>>,
    ) -> Result<Self, Error> {
        Self::cardinal(points, params, P::Scalar::ZERO)
    }

    /// The cardinal spline through `points` with `tension` `c`: the Catmull-Rom tangents
    /// scaled, `m_i · (1 − c)` (see [`HermiteSpline::catmull_rom`]). `c = 0` is Catmull-Rom,
    /// `c = 1` gives zero tangents (a curve that stops at every point); values outside
    /// `[0, 1]` are accepted (`c < 0` lengthens, `c > 1` reverses the tangents).
    ///
    /// # Errors
    /// As [`HermiteSpline::catmull_rom`]; [`Error::NonFinite`] also for a non-finite tension.
    ///
    /// ```
    /// use strak_curves::{HermiteSpline, Parameterization};
    ///
    /// let pts = [[0.0_f32, 0.0], [1.0, 1.0], [2.0, 0.0]];
    /// let c = HermiteSpline::<_, 4>::cardinal(&pts, Parameterization::Uniform, 0.5).unwrap();
    /// assert_eq!(c.tangents(), &[[0.5, 0.5], [0.5, 0.0], [0.5, -0.5]]);
    /// ```
    pub fn cardinal<'a>(
        points: &[P],
        params: impl Into<NodeSource<'a, P::Scalar>>,
        tension: P::Scalar,
    ) -> Result<Self, Error> {
        check_points::<P, N>(points, 2)?;
        if !tension.is_finite() {
            return Err(Error::NonFinite);
        }
        let nodes = params.into().resolve::<P, N>(points)?;
        let scale = 1.0 - tension.to_f64();
        let n = points.len() - 1;
        let mut tangents: Vec<P, N> = Vec::new();
        for i in 0..=n {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n));
            let (Some(qa), Some(qb), Some(ua), Some(ub)) =
                (points.get(a), points.get(b), nodes.get(a), nodes.get(b))
            else {
                return Err(Error::InvalidArgument);
            };
            let (qa, qb) = (qa.to_f64_array(), qb.to_f64_array());
            let du = ub.to_f64() - ua.to_f64();
            let m: [f64; MAX_DIM] = core::array::from_fn(|c| (qb[c] - qa[c]) / du * scale);
            let m = P::from_f64_slice(&m[..P::DIM]).ok_or(Error::OutOfRange)?;
            tangents.push(m).map_err(|_| Error::CapacityExceeded {
                capacity: N,
                required: points.len(),
            })?;
        }
        Self::new(points, &tangents, NodeSource::Given(&nodes))
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use crate::scalar::I16F16;
    use crate::{Error, HermiteSpline, ParamCurve, ParamCurveDeriv, Parameterization};

    const PTS: [[f64; 2]; 5] = [[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [6.0, 1.0]];
    const U: [f64; 5] = [0.0, 1.0, 3.0, 3.5, 5.0];

    #[test]
    fn catmull_rom_tangents_exact() {
        let c = HermiteSpline::<_, 8>::catmull_rom(&PTS, &U).unwrap();
        let t = c.tangents();
        assert_eq!(t[0], [1.0, 2.0]);
        assert_eq!(t[1], [3.0 / 3.0, 3.0 / 3.0]);
        assert_eq!(t[2], [3.0 / 2.5, -2.0 / 2.5]);
        assert_eq!(t[3], [3.0 / 2.0, -2.0 / 2.0]);
        assert_eq!(t[4], [2.0 / 1.5, 1.0 / 1.5]);
        for i in 0..5 {
            assert_eq!(c.eval(U[i]), PTS[i]);
        }
    }

    #[test]
    fn catmull_rom_is_c1() {
        let c = HermiteSpline::<_, 8>::catmull_rom(&PTS, Parameterization::ChordLength).unwrap();
        for i in 1..4 {
            let u = c.nodes()[i];
            let left = c.segment(i - 1).unwrap().deriv(u, 1);
            let right = c.deriv(u, 1);
            for k in 0..2 {
                assert!((left[k] - right[k]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn cardinal_scales_tangents() {
        let cr = HermiteSpline::<_, 8>::catmull_rom(&PTS, &U).unwrap();
        let c = HermiteSpline::<_, 8>::cardinal(&PTS, &U, 0.25).unwrap();
        for (a, b) in cr.tangents().iter().zip(c.tangents()) {
            for k in 0..2 {
                assert!((a[k] * 0.75 - b[k]).abs() < 1e-15);
            }
        }
        let stop = HermiteSpline::<_, 8>::cardinal(&PTS, &U, 1.0).unwrap();
        assert!(stop.tangents().iter().all(|m| *m == [0.0, 0.0]));
        assert_eq!(
            HermiteSpline::<_, 8>::cardinal(&PTS, &U, f64::NAN),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn two_points_give_a_line() {
        let c =
            HermiteSpline::<_, 2>::catmull_rom(&[[1.0_f64, 1.0], [3.0, 5.0]], &[0.0, 2.0]).unwrap();
        assert_eq!(c.eval(1.0), [2.0, 3.0]);
        assert_eq!(c.deriv(0.5, 1), [1.0, 2.0]);
        assert_eq!(c.deriv(0.5, 2), [0.0, 0.0]);
    }

    #[test]
    fn errors() {
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&PTS[..1], Parameterization::Uniform),
            Err(Error::TooFewPoints {
                required: 2,
                found: 1
            })
        );
        assert_eq!(
            HermiteSpline::<_, 4>::catmull_rom(&PTS, Parameterization::Uniform),
            Err(Error::CapacityExceeded {
                capacity: 4,
                required: 5
            })
        );
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&PTS, &U[..4]),
            Err(Error::LengthMismatch {
                expected: 5,
                found: 4
            })
        );
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&[[0.0], [f64::NAN]], Parameterization::Uniform),
            Err(Error::NonFinite)
        );
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&PTS, &[0.0, 1.0, 1.0, 2.0, 3.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&[[0.0], [0.0]], Parameterization::Centripetal),
            Err(Error::ZeroLengthInterval { index: 0 })
        );
        // slope 8000 per unit node: tangent fits, but 3·Δq/Δ = 24000 does not (I16F16)
        let f = |x: i32| I16F16::from_num(x);
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&[[f(0)], [f(8000)]], &[f(0), f(1)]),
            Err(Error::OutOfRange)
        );
        // tangent itself out of range
        let tiny = I16F16::from_bits(1);
        assert_eq!(
            HermiteSpline::<_, 8>::catmull_rom(&[[f(0)], [f(1)]], &[f(0), tiny]),
            Err(Error::OutOfRange)
        );
    }
}
