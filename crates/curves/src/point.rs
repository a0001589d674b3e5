//! Points and vectors of 1 to [`MAX_DIM`] coordinates: glam vectors and `[S; D]` arrays.
//!
//! [`Point`] is the vector-space interface every curve is written against. It is implemented
//! for glam's `Vec2`, `Vec3`, `Vec3A`, `Vec4` (f32) and `DVec2`, `DVec3`, `DVec4` (f64), and for
//! arrays `[S; D]` of any [`Scalar`] — the arrays are what fixed-point curves use.
//!
//! The method names (`plus`, `minus`, `times`, `lerp`) are chosen so that generic code always
//! runs the same operations in the same order, whatever the point type: `lerp` is the
//! convex combination `(1 − t)·a + t·b` of de Casteljau's algorithm (Farin, *Curves and
//! Surfaces for CAGD*, 5th ed., §2.3 "Linear Interpolation"), not glam's `a + (b − a)·t`.

use core::fmt::Debug;

use crate::scalar::Scalar;

/// The most coordinates a [`Point`] has (arrays `[S; D]` with `D > MAX_DIM` do not compile):
/// the interpolating constructors compute in `f64` arrays of this size
/// ([`Point::to_f64_array`]), and 8 covers every machine of the crate's users (up to 6 joints
/// and 2 auxiliary axes).
///
/// ```
/// use strak_curves::{MAX_DIM, Point};
/// let p: [f64; 6] = Point::from_coords(|i| i as f64);
/// assert_eq!(p.to_f64_array()[..6], [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
/// assert_eq!(p.to_f64_array().len(), MAX_DIM);
/// ```
pub const MAX_DIM: usize = 8;

/// A point (or vector) with [`Point::DIM`] coordinates of type [`Point::Scalar`].
///
/// ```
/// use strak_curves::Point;
/// use glam::Vec2;
///
/// let a = Vec2::new(0.0, 0.0);
/// let b = Vec2::new(2.0, 4.0);
/// assert_eq!(Point::lerp(a, b, 0.25), Vec2::new(0.5, 1.0));
/// let c: [f64; 3] = Point::from_coords(|i| i as f64);
/// assert_eq!(c.coord(2), 2.0);
/// ```
pub trait Point: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// The coordinate type.
    type Scalar: Scalar;
    /// The number of coordinates.
    const DIM: usize;

    /// Builds a point from its coordinates; `f` is called with `0..DIM`.
    fn from_coords(f: impl FnMut(usize) -> Self::Scalar) -> Self;

    /// Coordinate `i`; zero for `i >= DIM`.
    fn coord(&self, i: usize) -> Self::Scalar;

    /// The origin / zero vector.
    #[inline]
    fn zero() -> Self {
        Self::from_coords(|_| Self::Scalar::ZERO)
    }

    /// Coordinate-wise `self + other`.
    #[inline]
    fn plus(self, other: Self) -> Self {
        Self::from_coords(|i| self.coord(i) + other.coord(i))
    }

    /// Coordinate-wise `self − other`.
    #[inline]
    fn minus(self, other: Self) -> Self {
        Self::from_coords(|i| self.coord(i) - other.coord(i))
    }

    /// `self · s`.
    #[inline]
    fn times(self, s: Self::Scalar) -> Self {
        Self::from_coords(|i| self.coord(i) * s)
    }

    /// The convex combination `(1 − t)·self + t·other`, the step of de Casteljau's algorithm.
    #[inline]
    fn lerp(self, other: Self, t: Self::Scalar) -> Self {
        let s = Self::Scalar::ONE - t;
        Self::from_coords(|i| self.coord(i) * s + other.coord(i) * t)
    }

    /// The dot product.
    #[inline]
    fn dot(self, other: Self) -> Self::Scalar {
        let mut acc = Self::Scalar::ZERO;
        for i in 0..Self::DIM {
            acc += self.coord(i) * other.coord(i);
        }
        acc
    }

    /// The Euclidean norm `|self|`.
    #[inline]
    fn norm(self) -> Self::Scalar {
        self.dot(self).sqrt()
    }

    /// The largest coordinate magnitude, in `f64` (used by range checks).
    #[inline]
    fn max_abs(self) -> f64 {
        let mut m = 0.0_f64;
        for i in 0..Self::DIM {
            m = m.max(self.coord(i).to_f64().abs());
        }
        m
    }

    /// `true` when every coordinate is finite (always for fixed-point).
    #[inline]
    fn is_finite(self) -> bool {
        (0..Self::DIM).all(|i| self.coord(i).is_finite())
    }

    /// The coordinates as `f64` (unused trailing entries are zero).
    #[inline]
    fn to_f64_array(self) -> [f64; MAX_DIM] {
        let mut out = [0.0; MAX_DIM];
        for (i, o) in out.iter_mut().enumerate().take(Self::DIM) {
            *o = self.coord(i).to_f64();
        }
        out
    }

    /// The point with the given `f64` coordinates, or `None` when one is not finite or out of
    /// the scalar's range (missing coordinates are zero).
    #[inline]
    fn from_f64_slice(coords: &[f64]) -> Option<Self> {
        let mut ok = true;
        let p = Self::from_coords(|i| {
            let v = coords.get(i).copied().unwrap_or(0.0);
            Self::Scalar::from_f64(v).unwrap_or_else(|| {
                ok = false;
                Self::Scalar::ZERO
            })
        });
        ok.then_some(p)
    }
}

impl<S: Scalar, const D: usize> Point for [S; D] {
    type Scalar = S;
    const DIM: usize = {
        assert!(D <= MAX_DIM, "a point has at most MAX_DIM = 8 coordinates");
        D
    };

    #[inline]
    fn from_coords(f: impl FnMut(usize) -> S) -> Self {
        core::array::from_fn(f)
    }

    #[inline]
    fn coord(&self, i: usize) -> S {
        self.get(i).copied().unwrap_or(S::ZERO)
    }
}

macro_rules! impl_glam {
    ($t:ty, $s:ty, $d:literal) => {
        impl Point for $t {
            type Scalar = $s;
            const DIM: usize = $d;

            #[inline]
            fn from_coords(mut f: impl FnMut(usize) -> $s) -> Self {
                let a: [$s; $d] = core::array::from_fn(&mut f);
                <$t>::from_array(a)
            }

            #[inline]
            fn coord(&self, i: usize) -> $s {
                self.to_array().get(i).copied().unwrap_or(0.0)
            }

            #[inline]
            fn plus(self, other: Self) -> Self {
                self + other
            }

            #[inline]
            fn minus(self, other: Self) -> Self {
                self - other
            }

            #[inline]
            fn times(self, s: $s) -> Self {
                self * s
            }

            #[inline]
            fn lerp(self, other: Self, t: $s) -> Self {
                self * (1.0 - t) + other * t
            }
        }
    };
}

impl_glam!(glam::Vec2, f32, 2);
impl_glam!(glam::Vec3, f32, 3);
impl_glam!(glam::Vec3A, f32, 3);
impl_glam!(glam::Vec4, f32, 4);
impl_glam!(glam::DVec2, f64, 2);
impl_glam!(glam::DVec3, f64, 3);
impl_glam!(glam::DVec4, f64, 4);

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3, Vec3A};

    #[test]
    fn glam_and_arrays_agree_bit_for_bit() {
        let a = [0.1_f32, -2.5, 7.25];
        let b = [3.3_f32, 1.0e-3, -4.0];
        for t in [0.0_f32, 0.1, 0.5, 0.9, 1.0] {
            let arr = a.lerp(b, t);
            let v = Vec3::from_array(a).lerp_point(Vec3::from_array(b), t);
            let va = Vec3A::from_array(a).lerp_point(Vec3A::from_array(b), t);
            assert_eq!(arr, v.to_array());
            assert_eq!(arr, va.to_array());
        }
    }

    trait LerpPoint: Point {
        fn lerp_point(self, o: Self, t: Self::Scalar) -> Self {
            Point::lerp(self, o, t)
        }
    }
    impl<P: Point> LerpPoint for P {}

    #[test]
    fn coords_and_norm() {
        let p = DVec3::new(3.0, 4.0, 12.0);
        assert_eq!(Point::norm(p), 13.0);
        assert_eq!(p.coord(5), 0.0);
        assert_eq!(<[f64; 2]>::from_f64_slice(&[1.0]), Some([1.0, 0.0]));
        assert_eq!(<[f64; 2]>::from_f64_slice(&[f64::NAN]), None);
        assert_eq!(p.max_abs(), 12.0);
    }
}
