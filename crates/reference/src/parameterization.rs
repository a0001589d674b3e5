//! Node (parameter) choices for interpolation: uniform, chord-length (seeds/004,
//! "Intervallgrenzen") and centripetal.

use crate::vecops::vec_dist;

/// Uniform nodes `0, 1, …, n−1` (`n` nodes, spacing 1).
///
/// ```
/// assert_eq!(strak_ref::uniform_nodes(3), vec![0.0, 1.0, 2.0]);
/// ```
pub fn uniform_nodes(n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64).collect()
}

/// Chord-length parameterization (seeds/004, "Intervallgrenzen"): `t_0 = 0` and
/// `t_{i+1} = t_i + Δ_i` with `Δ_i = |P_i − P_{i+1}|` (Euclidean distance). Empty input gives an
/// empty vector.
///
/// ```
/// let t = strak_ref::chord_length_nodes(&[vec![0.0, 0.0], vec![3.0, 4.0], vec![3.0, 5.0]]);
/// assert_eq!(t, vec![0.0, 5.0, 6.0]);
/// ```
pub fn chord_length_nodes(pts: &[Vec<f64>]) -> Vec<f64> {
    cumulative(pts, |d| d)
}

/// Centripetal parameterization: `t_0 = 0`, `t_{i+1} = t_i + √|P_i − P_{i+1}|`.
///
/// ```
/// let t = strak_ref::centripetal_nodes(&[vec![0.0], vec![4.0], vec![13.0]]);
/// assert_eq!(t, vec![0.0, 2.0, 5.0]);
/// ```
pub fn centripetal_nodes(pts: &[Vec<f64>]) -> Vec<f64> {
    cumulative(pts, f64::sqrt)
}

fn cumulative(pts: &[Vec<f64>], f: impl Fn(f64) -> f64) -> Vec<f64> {
    if pts.is_empty() {
        return Vec::new();
    }
    let mut t = vec![0.0];
    for w in pts.windows(2) {
        let last = t[t.len() - 1];
        t.push(last + f(vec_dist(&w[0], &w[1])));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chord_length_sums_distances() {
        let pts = vec![
            vec![1.0, 1.0, 1.0],
            vec![1.0, 1.0, 3.0],
            vec![4.0, 5.0, 3.0],
        ];
        assert_eq!(chord_length_nodes(&pts), vec![0.0, 2.0, 7.0]);
        assert_eq!(chord_length_nodes(&pts[..1]), vec![0.0]);
        assert!(chord_length_nodes(&[]).is_empty());
    }

    #[test]
    fn centripetal_and_uniform() {
        let pts = vec![vec![0.0, 0.0], vec![0.0, 9.0], vec![16.0, 9.0]];
        assert_eq!(centripetal_nodes(&pts), vec![0.0, 3.0, 7.0]);
        assert_eq!(uniform_nodes(0), Vec::<f64>::new());
        assert_eq!(uniform_nodes(4), vec![0.0, 1.0, 2.0, 3.0]);
    }
}
