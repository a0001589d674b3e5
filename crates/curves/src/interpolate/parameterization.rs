//! Interpolation nodes: the parameter values `u_0 < u_1 < … < u_n`
//! at which an interpolating curve passes through its points.
//!
//! The nodes are either given by the caller ([`NodeSource::Given`], checked with
//! [`validate_interpolation_nodes`]) or computed from the points by a [`Parameterization`]:
//! uniform, chord-length (`Δ_i = |P_{i+1} − P_i|`) or centripetal (`Δ_i = √|P_{i+1} − P_i|`)
//! (Piegl & Tiller, *The NURBS Book*, 2nd ed., §9.2.1; Farin, *Curves and Surfaces for CAGD*,
//! 5th ed., §7.7 "Finding a Knot Sequence"; Lee, "Choosing nodes in parametric curve
//! interpolation", *Computer-Aided Design* 21(6), 1989).

use heapless::Vec;

use crate::error::Error;
use crate::point::{MAX_DIM, Point};
use crate::scalar::Scalar;

/// How to compute interpolation nodes from the points.
///
/// All three start at `u_0 = 0`:
/// - `Uniform`: `u_i = i`;
/// - `ChordLength`: `u_{i+1} = u_i + |q_{i+1} − q_i|`;
/// - `Centripetal`: `u_{i+1} = u_i + √|q_{i+1} − q_i|` (Lee 1989).
///
/// Uniform nodes make a curve built on them affinely invariant; chord-length and
/// centripetal nodes change under non-uniform scaling, so such curves are invariant under
/// similarities (rotations, translations, uniform scaling) only.
///
/// The sums are formed in `f64` and then rounded to the scalar type. Under chord-length and
/// centripetal parameterization two equal consecutive points give an empty interval, which
/// is rejected with [`Error::ZeroLengthInterval`]; so is an interval that rounds to zero
/// length in the scalar type.
///
/// ```
/// use strak_curves::Parameterization;
///
/// let pts = [[0.0_f64, 0.0], [3.0, 4.0], [3.0, 8.0]];
/// let u = Parameterization::ChordLength.nodes::<_, 4>(&pts).unwrap();
/// assert_eq!(u.as_slice(), &[0.0, 5.0, 9.0]);
/// let u = Parameterization::Centripetal.nodes::<_, 4>(&pts).unwrap();
/// assert_eq!(u.as_slice(), &[0.0, 5.0_f64.sqrt(), 5.0_f64.sqrt() + 2.0]);
/// let u = Parameterization::Uniform.nodes::<_, 4>(&pts).unwrap();
/// assert_eq!(u.as_slice(), &[0.0, 1.0, 2.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Parameterization {
    /// Equally spaced nodes `0, 1, 2, …`.
    Uniform,
    /// Node spacing equal to the distance of consecutive points (chord length).
    ChordLength,
    /// Node spacing equal to the square root of the distance of consecutive points.
    Centripetal,
}

impl Parameterization {
    /// The nodes for `points`, starting at 0.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when more than `N` points are given, [`Error::NonFinite`]
    /// for a NaN or infinite coordinate, [`Error::ZeroLengthInterval`] for two equal
    /// consecutive points (chord-length, centripetal) or an interval that rounds to zero,
    /// [`Error::OutOfRange`] when a node does not fit the scalar type.
    ///
    /// ```
    /// use strak_curves::{Error, Parameterization};
    ///
    /// let pts = [[1.0_f32, 1.0], [1.0, 1.0]];
    /// assert_eq!(
    ///     Parameterization::ChordLength.nodes::<_, 4>(&pts),
    ///     Err(Error::ZeroLengthInterval { index: 0 })
    /// );
    /// ```
    pub fn nodes<P: Point, const N: usize>(self, points: &[P]) -> Result<Vec<P::Scalar, N>, Error> {
        if points.len() > N {
            return Err(Error::CapacityExceeded {
                capacity: N,
                required: points.len(),
            });
        }
        if !points.iter().all(|p| p.is_finite()) {
            return Err(Error::NonFinite);
        }
        let mut out: Vec<P::Scalar, N> = Vec::new();
        let mut acc = 0.0_f64;
        let mut prev: Option<(P::Scalar, [f64; MAX_DIM])> = None;
        for (i, p) in points.iter().enumerate() {
            let c = p.to_f64_array();
            if let Some((prev_node, prev_c)) = prev {
                let step = match self {
                    Parameterization::Uniform => 1.0,
                    Parameterization::ChordLength => distance(prev_c, c),
                    Parameterization::Centripetal => libm::sqrt(distance(prev_c, c)),
                };
                if step == 0.0 {
                    return Err(Error::ZeroLengthInterval { index: i - 1 });
                }
                acc += step;
                let node = <P::Scalar as Scalar>::from_f64(acc).ok_or(Error::OutOfRange)?;
                if node <= prev_node {
                    return Err(Error::ZeroLengthInterval { index: i - 1 });
                }
                push(&mut out, node)?;
                prev = Some((node, c));
            } else {
                push(&mut out, P::Scalar::ZERO)?;
                prev = Some((P::Scalar::ZERO, c));
            }
        }
        Ok(out)
    }
}

fn push<S, const N: usize>(v: &mut Vec<S, N>, x: S) -> Result<(), Error> {
    v.push(x).map_err(|_| Error::CapacityExceeded {
        capacity: N,
        required: N + 1,
    })
}

/// Euclidean distance of two points given as `f64` coordinates.
fn distance(a: [f64; MAX_DIM], b: [f64; MAX_DIM]) -> f64 {
    let mut s = 0.0;
    for (x, y) in a.iter().zip(b.iter()) {
        let d = y - x;
        s += d * d;
    }
    libm::sqrt(s)
}

/// Checks caller-given interpolation nodes: every node finite and within the scalar's range
/// ([`Scalar::LIMIT`]), strictly increasing, and the whole span `u_n − u_0` within range.
///
/// # Errors
/// [`Error::NonFinite`], [`Error::NodesNotIncreasing`] (index of the first node that is not
/// larger than its predecessor), [`Error::OutOfRange`].
///
/// ```
/// use strak_curves::{validate_interpolation_nodes, Error};
///
/// assert_eq!(validate_interpolation_nodes(&[0.0_f64, 0.5, 2.0]), Ok(()));
/// assert_eq!(
///     validate_interpolation_nodes(&[0.0_f64, 1.0, 1.0]),
///     Err(Error::NodesNotIncreasing { index: 2 })
/// );
/// ```
pub fn validate_interpolation_nodes<S: Scalar>(nodes: &[S]) -> Result<(), Error> {
    if !nodes.iter().all(|u| u.is_finite()) {
        return Err(Error::NonFinite);
    }
    if !nodes.iter().all(|u| S::fits(u.to_f64())) {
        return Err(Error::OutOfRange);
    }
    for (i, w) in nodes.windows(2).enumerate() {
        if let [a, b] = w
            && b <= a
        {
            return Err(Error::NodesNotIncreasing { index: i + 1 });
        }
    }
    if let (Some(first), Some(last)) = (nodes.first(), nodes.last())
        && !S::fits(last.to_f64() - first.to_f64())
    {
        return Err(Error::OutOfRange);
    }
    Ok(())
}

/// Where the nodes of an interpolating curve come from: given by the caller, or computed from
/// the points by a [`Parameterization`].
///
/// Constructors take `impl Into<NodeSource>`, so both a node slice and a parameterization can
/// be passed directly.
///
/// ```
/// use strak_curves::{NodeSource, Parameterization};
///
/// let pts = [[0.0_f64], [2.0], [3.0]];
/// let given: NodeSource<'_, f64> = (&[0.0, 1.0, 4.0][..]).into();
/// assert_eq!(given.resolve::<_, 3>(&pts).unwrap().as_slice(), &[0.0, 1.0, 4.0]);
/// let chord: NodeSource<'_, f64> = Parameterization::ChordLength.into();
/// assert_eq!(chord.resolve::<_, 3>(&pts).unwrap().as_slice(), &[0.0, 2.0, 3.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NodeSource<'a, S> {
    /// Nodes given by the caller: one per point, finite, strictly increasing.
    Given(&'a [S]),
    /// Nodes computed from the points.
    Computed(Parameterization),
}

impl<S: Scalar> NodeSource<'_, S> {
    /// The nodes for `points`: the given ones after [`validate_interpolation_nodes`] and a
    /// length check, or the computed ones.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when the number of given nodes differs from the number of
    /// points, [`Error::CapacityExceeded`] beyond `N` nodes, and the errors of
    /// [`validate_interpolation_nodes`] and [`Parameterization::nodes`].
    ///
    /// ```
    /// use strak_curves::{Error, NodeSource};
    ///
    /// let pts = [[0.0_f32], [2.0], [3.0]];
    /// let src = NodeSource::Given(&[0.0_f32, 1.0][..]);
    /// assert_eq!(
    ///     src.resolve::<_, 3>(&pts),
    ///     Err(Error::LengthMismatch { expected: 3, found: 2 })
    /// );
    /// ```
    pub fn resolve<P: Point<Scalar = S>, const N: usize>(
        self,
        points: &[P],
    ) -> Result<Vec<S, N>, Error> {
        match self {
            NodeSource::Given(nodes) => {
                if nodes.len() != points.len() {
                    return Err(Error::LengthMismatch {
                        expected: points.len(),
                        found: nodes.len(),
                    });
                }
                validate_interpolation_nodes(nodes)?;
                Vec::from_slice(nodes).map_err(|_| Error::CapacityExceeded {
                    capacity: N,
                    required: nodes.len(),
                })
            }
            NodeSource::Computed(p) => p.nodes::<P, N>(points),
        }
    }
}

impl<'a, S> From<&'a [S]> for NodeSource<'a, S> {
    fn from(nodes: &'a [S]) -> Self {
        NodeSource::Given(nodes)
    }
}

impl<'a, S, const M: usize> From<&'a [S; M]> for NodeSource<'a, S> {
    fn from(nodes: &'a [S; M]) -> Self {
        NodeSource::Given(nodes.as_slice())
    }
}

impl<S> From<Parameterization> for NodeSource<'_, S> {
    fn from(p: Parameterization) -> Self {
        NodeSource::Computed(p)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_possible_truncation)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    #[test]
    fn uniform_nodes() {
        let pts = [[5.0_f64, 1.0], [5.0, 1.0], [7.0, 0.0], [0.0, 0.0]];
        let u = Parameterization::Uniform.nodes::<_, 4>(&pts).unwrap();
        assert_eq!(u.as_slice(), &[0.0, 1.0, 2.0, 3.0]);
    }

    #[test]
    fn chord_length_nodes() {
        let pts = [[0.0_f64, 0.0], [3.0, 4.0], [3.0, 5.0], [-3.0, 13.0]];
        let u = Parameterization::ChordLength.nodes::<_, 8>(&pts).unwrap();
        assert_eq!(u.as_slice(), &[0.0, 5.0, 6.0, 16.0]);
    }

    #[test]
    fn centripetal_nodes() {
        let pts = [[0.0_f64, 0.0], [0.0, 4.0], [0.0, 13.0]];
        let u = Parameterization::Centripetal.nodes::<_, 8>(&pts).unwrap();
        assert_eq!(u.as_slice(), &[0.0, 2.0, 5.0]);
    }

    #[test]
    fn fixed_point_nodes() {
        let p = |x: i16, y: i16| [I16F16::from_num(x), I16F16::from_num(y)];
        let pts = [p(0, 0), p(3, 4), p(6, 8)];
        let u = Parameterization::ChordLength.nodes::<_, 3>(&pts).unwrap();
        assert_eq!(
            u.as_slice(),
            &[
                I16F16::from_num(0),
                I16F16::from_num(5),
                I16F16::from_num(10)
            ]
        );
    }

    #[test]
    fn zero_length_interval() {
        let pts = [[0.0_f64, 0.0], [1.0, 0.0], [1.0, 0.0]];
        for p in [Parameterization::ChordLength, Parameterization::Centripetal] {
            assert_eq!(
                p.nodes::<_, 4>(&pts),
                Err(Error::ZeroLengthInterval { index: 1 })
            );
        }
        assert!(Parameterization::Uniform.nodes::<_, 4>(&pts).is_ok());
    }

    #[test]
    fn interval_rounding_to_zero_is_rejected() {
        // 1e8 + 1 rounds to 1e8 in f32 (spacing 8 there): the second interval vanishes.
        let pts = [[0.0_f32, 0.0], [1.0e8, 0.0], [1.0e8, 1.0]];
        assert_eq!(
            Parameterization::ChordLength.nodes::<_, 3>(&pts),
            Err(Error::ZeroLengthInterval { index: 1 })
        );
    }

    #[test]
    fn non_finite_and_capacity() {
        let pts = [[0.0_f64, f64::NAN], [1.0, 0.0]];
        assert_eq!(
            Parameterization::Uniform.nodes::<_, 4>(&pts),
            Err(Error::NonFinite)
        );
        let pts = [[0.0_f64], [1.0], [2.0]];
        assert_eq!(
            Parameterization::Uniform.nodes::<_, 2>(&pts),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
    }

    #[test]
    fn out_of_range_nodes() {
        let big = I16F16::from_num(10000);
        let pts = [[big], [-big], [big]];
        assert_eq!(
            Parameterization::ChordLength.nodes::<_, 3>(&pts),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn validate_nodes_errors() {
        assert_eq!(validate_interpolation_nodes::<f64>(&[]), Ok(()));
        assert_eq!(
            validate_interpolation_nodes(&[0.0_f32, f32::INFINITY]),
            Err(Error::NonFinite)
        );
        assert_eq!(
            validate_interpolation_nodes(&[0.0_f32, 2.0, 1.0]),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
        let lim = I16F16::from_num(16000);
        assert_eq!(
            validate_interpolation_nodes(&[-lim, lim]),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            validate_interpolation_nodes(&[I16F16::from_num(20000)]),
            Err(Error::OutOfRange)
        );
    }

    #[test]
    fn node_source_resolves() {
        let pts = [[0.0_f64], [1.0], [2.0]];
        let src: NodeSource<'_, f64> = (&[0.0, 2.0, 3.0]).into();
        assert_eq!(
            src.resolve::<_, 3>(&pts).unwrap().as_slice(),
            &[0.0, 2.0, 3.0]
        );
        assert_eq!(
            NodeSource::Given(&[0.0, 2.0, 3.0][..]).resolve::<_, 2>(&pts),
            Err(Error::CapacityExceeded {
                capacity: 2,
                required: 3
            })
        );
        assert_eq!(
            NodeSource::Given(&[0.0, 2.0, 2.0][..]).resolve::<_, 3>(&pts),
            Err(Error::NodesNotIncreasing { index: 2 })
        );
    }
}
