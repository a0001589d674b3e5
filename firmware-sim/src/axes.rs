//! The axes strak-sim plays: 1 to [`MAX_AXES`] coordinates per point, and their names in the
//! CSV headers, the summary and the plots.

/// The largest number of coordinates per point (axes) strak-sim builds and plays.
pub const MAX_AXES: usize = 6;

/// The names of the axes, in order: `x`, `y`, `z`, `w`, then `x5`, `x6`.
pub const AXIS_NAMES: [&str; MAX_AXES] = ["x", "y", "z", "w", "x5", "x6"];

/// The names of the first `axes` axes (all of them for more than [`MAX_AXES`]).
///
/// ```
/// assert_eq!(strak_sim::axes::names(3), ["x", "y", "z"]);
/// ```
pub fn names(axes: usize) -> &'static [&'static str] {
    &AXIS_NAMES[..axes.min(MAX_AXES)]
}

/// Calls `$f::<…, D>(args)` with the const generic `D` equal to the runtime axis count `$d`
/// (1 to [`MAX_AXES`]); any other count evaluates `$otherwise`.
#[macro_export]
macro_rules! with_axes {
    ($d:expr, $f:ident::<$($g:tt),*>($($arg:expr),* $(,)?), $otherwise:expr) => {
        match $d {
            1 => $f::<$($g,)* 1>($($arg),*),
            2 => $f::<$($g,)* 2>($($arg),*),
            3 => $f::<$($g,)* 3>($($arg),*),
            4 => $f::<$($g,)* 4>($($arg),*),
            5 => $f::<$($g,)* 5>($($arg),*),
            6 => $f::<$($g,)* 6>($($arg),*),
            _ => $otherwise,
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn count<T, const D: usize>(_: T) -> usize {
        D
    }

    #[test]
    fn dispatch_reaches_every_count() {
        for d in 1..=MAX_AXES {
            assert_eq!(with_axes!(d, count::<()>(()), 0), d);
        }
        assert_eq!(with_axes!(7, count::<()>(()), 0), 0);
        assert_eq!(names(2), ["x", "y"]);
        assert_eq!(names(6)[5], "x6");
    }
}
