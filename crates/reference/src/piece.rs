//! Locating the piece of a piecewise curve that a parameter falls into.

/// Clamps `u` to `[breaks[0], breaks[n]]` and returns `(i, u_clamped)` where piece `i` is
/// `[breaks[i], breaks[i+1]]`: the last `i ≤ n − 1` with `breaks[i] ≤ u`. So at an inner
/// boundary the piece *starting* there is used, and at the end of the domain the last piece.
/// This is the convention of `strak-curves`' `ParamCurveDeriv`.
///
/// # Panics
/// If `breaks` has fewer than two entries.
///
/// ```
/// let b = [0.0, 1.0, 3.0];
/// assert_eq!(strak_ref::find_piece(&b, 1.0), (1, 1.0));
/// assert_eq!(strak_ref::find_piece(&b, 3.0), (1, 3.0));
/// assert_eq!(strak_ref::find_piece(&b, -5.0), (0, 0.0));
/// ```
pub fn find_piece(breaks: &[f64], u: f64) -> (usize, f64) {
    assert!(
        breaks.len() >= 2,
        "find_piece: need at least two breakpoints"
    );
    let n = breaks.len() - 1;
    let u = u.clamp(breaks[0], breaks[n]);
    let mut i = 0;
    while i + 1 < n && breaks[i + 1] <= u {
        i += 1;
    }
    (i, u)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_and_clamping() {
        let b = [0.0, 0.5, 2.0, 4.0];
        assert_eq!(find_piece(&b, 0.0), (0, 0.0));
        assert_eq!(find_piece(&b, 0.49), (0, 0.49));
        assert_eq!(find_piece(&b, 0.5), (1, 0.5));
        assert_eq!(find_piece(&b, 2.0), (2, 2.0));
        assert_eq!(find_piece(&b, 4.0), (2, 4.0));
        assert_eq!(find_piece(&b, 9.0), (2, 4.0));
        assert_eq!(find_piece(&[1.0, 2.0], 1.5), (0, 1.5));
    }
}
