//! Constant speed along the arc length: `s(t) = v·t`.

use heapless::Vec;

use super::motion::{MotionProfile, ProfileZone};
use super::scurve::{check_length, check_limit};
use crate::error::Error;

impl<const Z: usize> MotionProfile<Z> {
    /// The motion `s(t) = speed·t` over `length`: one zone with one phase of constant speed,
    /// duration `length/speed`. It starts and ends at `speed` (not at rest; the acceleration
    /// is zero throughout). `Z ≥ 1`.
    ///
    /// # Errors
    /// [`Error::EmptyPath`] unless `length` is finite and positive; [`Error::InvalidLimit`]
    /// unless `speed` is finite and positive;
    /// [`Error::TooLong`] for a duration beyond `u32::MAX` ticks at 100 Hz (infinite
    /// included); [`Error::ZoneCapacityExceeded`] for `Z = 0`.
    ///
    /// ```
    /// use strak_trajectory::MotionProfile;
    /// let m = MotionProfile::<1>::constant_speed(10.0, 4.0)?;
    /// assert_eq!(m.duration(), 2.5);
    /// assert_eq!(m.state(1.0).s, 4.0);
    /// assert_eq!(m.state(m.duration()).v, 4.0);
    /// # Ok::<(), strak_trajectory::Error>(())
    /// ```
    pub fn constant_speed(length: f64, speed: f64) -> Result<Self, Error> {
        let length = check_length(length)?;
        let speed = check_limit(speed)?;
        let mut zone = ProfileZone::new(0.0, length, speed, 0.0, 0.0);
        zone.v_start = speed;
        zone.v_end = speed;
        zone.push((0.0, 0.0, speed), length / speed, 0.0, 0.0);
        let mut zones = Vec::new();
        zones.push(zone).map_err(|_| Error::ZoneCapacityExceeded {
            capacity: Z,
            required: 1,
        })?;
        MotionProfile::from_zones(zones, length)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_in_time() {
        let m = MotionProfile::<2>::constant_speed(3.0, 1.5).unwrap();
        assert_eq!(m.duration(), 2.0);
        for k in 0..=20 {
            let t = 0.1 * f64::from(k);
            let st = m.state(t);
            assert!((st.s - 1.5 * t).abs() < 1e-15);
            assert_eq!((st.v, st.a, st.j), (1.5, 0.0, 0.0));
        }
        assert_eq!(m.state(-1.0).s, 0.0);
        assert_eq!(m.state(5.0).s, 3.0);
        assert_eq!(m.zones().len(), 1);
        assert_eq!(m.phases().count(), 1);
    }

    #[test]
    fn errors() {
        assert_eq!(
            MotionProfile::<1>::constant_speed(0.0, 1.0),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            MotionProfile::<1>::constant_speed(1.0, 0.0),
            Err(Error::InvalidLimit)
        );
        assert_eq!(
            MotionProfile::<1>::constant_speed(1e300, 1e-300),
            Err(Error::TooLong)
        );
        assert_eq!(
            MotionProfile::<0>::constant_speed(1.0, 1.0),
            Err(Error::ZoneCapacityExceeded {
                capacity: 0,
                required: 1
            })
        );
    }
}
