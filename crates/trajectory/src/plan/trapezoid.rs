//! The trapezoidal velocity profile: constant acceleration, cruise, constant deceleration.

use super::motion::MotionProfile;
use super::scurve::{check_length, check_limit, rest_to_rest};
use crate::error::Error;

impl<const Z: usize> MotionProfile<Z> {
    /// The time-optimal acceleration-limited motion over `length` from rest to rest: speed
    /// `≤ v_max`, `|a| ≤ a_max`, the acceleration jumping between `a_max`, 0 and `−a_max`
    /// (no jerk limit). One zone; `Z ≥ 1`.
    ///
    /// When `length ≥ v_max²/a_max` the speed reaches `v_max` and `T = length/v_max +
    /// v_max/a_max`; otherwise the profile is a triangle with peak `√(a_max·length)` and
    /// `T = 2·√(length/a_max)`. (The double S of [`MotionProfile::scurve`] with an infinite
    /// jerk limit.)
    ///
    /// # Errors
    /// [`Error::EmptyPath`] unless `length` is finite and positive; [`Error::InvalidLimit`]
    /// unless both limits are finite and positive;
    /// [`Error::TooLong`] for a duration beyond `u32::MAX` ticks at 100 Hz (infinite
    /// included); [`Error::ZoneCapacityExceeded`] for `Z = 0`.
    ///
    /// ```
    /// use strak_trajectory::MotionProfile;
    /// let m = MotionProfile::<1>::trapezoid(10.0, 2.0, 1.0)?;
    /// assert!((m.duration() - (10.0 / 2.0 + 2.0 / 1.0)).abs() < 1e-12);
    /// assert_eq!(m.state(0.5).a, 1.0);
    /// assert_eq!(m.state(3.0).v, 2.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn trapezoid(length: f64, v_max: f64, a_max: f64) -> Result<Self, Error> {
        let length = check_length(length)?;
        rest_to_rest(
            length,
            check_limit(v_max)?,
            check_limit(a_max)?,
            f64::INFINITY,
        )
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn closed_form(l: f64, v: f64, a: f64) -> f64 {
        if l >= v * v / a {
            l / v + v / a
        } else {
            2.0 * (l / a).sqrt()
        }
    }

    #[test]
    fn duration_closed_form() {
        for &(l, v, a) in &[
            (10.0, 2.0, 1.0),
            (4.0, 2.0, 1.0),
            (1.0, 2.0, 1.0),
            (0.37, 5.0, 3.0),
            (123.0, 7.5, 0.25),
        ] {
            let m = MotionProfile::<1>::trapezoid(l, v, a).unwrap();
            let exact = closed_form(l, v, a);
            assert!(
                (m.duration() - exact).abs() <= 1e-12 * exact,
                "{l} {v} {a}: {} vs {exact}",
                m.duration()
            );
            // speed and acceleration within the limits, jerk zero inside the phases
            let n = 4000;
            for k in 0..=n {
                let st = m.state(m.duration() * k as f64 / n as f64);
                assert!(st.v <= v * (1.0 + 1e-12) && st.v >= -1e-12);
                assert!(st.a.abs() <= a);
                assert_eq!(st.j, 0.0);
            }
            assert_eq!(m.state(m.duration()).s, l);
        }
    }

    #[test]
    fn triangle_peak() {
        // l = 1 < v²/a = 4: peak √(a l) = 1 at t = 1
        let m = MotionProfile::<1>::trapezoid(1.0, 2.0, 1.0).unwrap();
        let st = m.state(1.0);
        assert!((st.v - 1.0).abs() < 1e-12 && (st.s - 0.5).abs() < 1e-12);
        // accelerate, decelerate (and at most a cruise of a few ulp for the rounding)
        assert_eq!(m.phases().filter(|p| p.duration > 1e-12).count(), 2);
    }

    #[test]
    fn errors() {
        assert_eq!(
            MotionProfile::<1>::trapezoid(-1.0, 1.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::trapezoid(1.0, 0.0, 1.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::trapezoid(1.0, 1.0, f64::NAN),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<0>::trapezoid(1.0, 1.0, 1.0),
            Err(Error::ZoneCapacityExceeded {
                capacity: 0,
                required: 1
            })
        );
    }
}
