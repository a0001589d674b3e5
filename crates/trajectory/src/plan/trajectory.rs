//! A trajectory: the curve and the time law along it, given once, as the compiler takes them.

use strak_curves::ParamCurveDeriv;

use super::timing::Timing;

/// A trajectory: a geometric path (the curve) together with the time law that says where on
/// it the motion is at each time ("a path on which a timing law is specified": Siciliano,
/// Sciavicco, Villani & Oriolo, *Robotics: Modelling, Planning and Control*, §4.1). It is
/// what [`compile`](crate::compile()) turns into a path of pieces in control ticks.
///
/// A planned law holds its curve and is a trajectory itself
/// ([`PathTiming`](crate::PathTiming)); any other law is paired with its curve by
/// [`Along`].
///
/// ```
/// use strak_curves::{Bezier, ParamCurve};
/// use strak_trajectory::{Along, ParameterTiming, PathTiming, Timing, Trajectory};
///
/// let line = Bezier::new([[0.0, 0.0], [3.0, 4.0]])?;
/// let planned = PathTiming::<_, 16, 1>::constant_speed(&line, 10.0)?;
/// assert_eq!(planned.curve().domain(), (0.0, 1.0));
/// assert!((planned.law().duration() - 0.5).abs() < 1e-9);
///
/// let law = ParameterTiming::at_rate(&line, 2.0)?;
/// let paired = Along::new(&line, &law);
/// assert_eq!(paired.law().duration(), 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Trajectory {
    /// The curve.
    type Curve: ParamCurveDeriv + ?Sized;
    /// The time law along the curve.
    type Law: Timing + ?Sized;

    /// The curve.
    fn curve(&self) -> &Self::Curve;

    /// The time law along [`curve`](Self::curve).
    fn law(&self) -> &Self::Law;
}

/// A time law paired with the curve it runs along: the [`Trajectory`] of a law that does not
/// hold its curve (a [`ParameterTiming`](crate::ParameterTiming), a law of your own).
///
/// ```
/// use strak_curves::Bezier;
/// use strak_trajectory::{Along, CompileOptions, ParameterTiming, Path, compile};
///
/// let curve = Bezier::new([[0.0, 0.0], [5.0, 0.0], [5.0, 5.0]])?;
/// let law = ParameterTiming::at_rate(&curve, 4.0)?; // u from 0 to 1 in 0.25 s
/// let path: Path<f64, 2, 16> = compile(&Along::new(&curve, &law), 1_000.0, &CompileOptions::new())?;
/// assert_eq!(path.ticks(), 250);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Along<'a, C: ?Sized, T: ?Sized> {
    curve: &'a C,
    law: &'a T,
}

impl<'a, C: ?Sized, T: ?Sized> Along<'a, C, T> {
    /// The law `law` along `curve`.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{Along, ParameterTiming, Trajectory};
    /// let curve = Bezier::new([[0.0, 0.0], [1.0, 1.0]])?;
    /// let law = ParameterTiming::at_rate(&curve, 1.0)?;
    /// assert!(core::ptr::eq(Along::new(&curve, &law).curve(), &curve));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub const fn new(curve: &'a C, law: &'a T) -> Self {
        Along { curve, law }
    }
}

/// Copying shares the references (neither the curve nor the law need be `Clone`).
impl<C: ?Sized, T: ?Sized> Clone for Along<'_, C, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C: ?Sized, T: ?Sized> Copy for Along<'_, C, T> {}

impl<C: ParamCurveDeriv + ?Sized, T: Timing + ?Sized> Trajectory for Along<'_, C, T> {
    type Curve = C;
    type Law = T;

    fn curve(&self) -> &C {
        self.curve
    }

    fn law(&self) -> &T {
        self.law
    }
}
