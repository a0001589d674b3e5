//! Plain coordinate-vector helpers for points given as `Vec<f64>` / `&[f64]`.

/// The zero vector of dimension `dim`.
///
/// ```
/// assert_eq!(strak_ref::vec_zero(3), vec![0.0, 0.0, 0.0]);
/// ```
pub fn vec_zero(dim: usize) -> Vec<f64> {
    vec![0.0; dim]
}

/// Coordinate-wise sum `a + b`.
///
/// # Panics
/// If the dimensions differ.
///
/// ```
/// assert_eq!(strak_ref::vec_add(&[1.0, 2.0], &[3.0, 5.0]), vec![4.0, 7.0]);
/// ```
pub fn vec_add(a: &[f64], b: &[f64]) -> Vec<f64> {
    assert_eq!(a.len(), b.len(), "vec_add: dimension mismatch");
    a.iter().zip(b).map(|(x, y)| x + y).collect()
}

/// Coordinate-wise difference `a − b`.
///
/// # Panics
/// If the dimensions differ.
///
/// ```
/// assert_eq!(strak_ref::vec_sub(&[1.0, 2.0], &[3.0, 5.0]), vec![-2.0, -3.0]);
/// ```
pub fn vec_sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    assert_eq!(a.len(), b.len(), "vec_sub: dimension mismatch");
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// Scalar multiple `s · a`.
///
/// ```
/// assert_eq!(strak_ref::vec_scale(&[1.0, -2.0], 3.0), vec![3.0, -6.0]);
/// ```
pub fn vec_scale(a: &[f64], s: f64) -> Vec<f64> {
    a.iter().map(|x| s * x).collect()
}

/// Adds `s · a` to `acc` in place (`acc += s a`).
///
/// # Panics
/// If the dimensions differ.
///
/// ```
/// let mut acc = vec![1.0, 1.0];
/// strak_ref::vec_add_scaled(&mut acc, &[2.0, 4.0], 0.5);
/// assert_eq!(acc, vec![2.0, 3.0]);
/// ```
pub fn vec_add_scaled(acc: &mut [f64], a: &[f64], s: f64) {
    assert_eq!(acc.len(), a.len(), "vec_add_scaled: dimension mismatch");
    for (x, y) in acc.iter_mut().zip(a) {
        *x += s * y;
    }
}

/// Dot product `⟨a, b⟩`.
///
/// # Panics
/// If the dimensions differ.
///
/// ```
/// assert_eq!(strak_ref::vec_dot(&[1.0, 2.0], &[3.0, 4.0]), 11.0);
/// ```
pub fn vec_dot(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "vec_dot: dimension mismatch");
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm `‖a‖ = √⟨a, a⟩`.
///
/// ```
/// assert_eq!(strak_ref::vec_norm(&[3.0, 4.0]), 5.0);
/// ```
pub fn vec_norm(a: &[f64]) -> f64 {
    vec_dot(a, a).sqrt()
}

/// Euclidean distance `‖a − b‖`.
///
/// ```
/// assert_eq!(strak_ref::vec_dist(&[1.0, 1.0], &[4.0, 5.0]), 5.0);
/// ```
pub fn vec_dist(a: &[f64], b: &[f64]) -> f64 {
    vec_norm(&vec_sub(a, b))
}

/// Sum `Σ w_i p_i` of points `pts` with scalar weights `w` (all points of one dimension).
///
/// # Panics
/// If `pts` is empty, the lengths differ, or the dimensions differ.
///
/// ```
/// let p = strak_ref::weighted_sum(&[vec![1.0, 0.0], vec![0.0, 2.0]], &[0.5, 0.25]);
/// assert_eq!(p, vec![0.5, 0.5]);
/// ```
pub fn weighted_sum(pts: &[Vec<f64>], w: &[f64]) -> Vec<f64> {
    assert!(!pts.is_empty(), "weighted_sum: no points");
    assert_eq!(pts.len(), w.len(), "weighted_sum: length mismatch");
    let mut acc = vec_zero(pts[0].len());
    for (p, &wi) in pts.iter().zip(w) {
        vec_add_scaled(&mut acc, p, wi);
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basic_ops() {
        assert_eq!(vec_add(&[1.0], &[2.0]), vec![3.0]);
        assert_eq!(vec_sub(&[1.0, 0.0], &[0.0, 1.0]), vec![1.0, -1.0]);
        assert_eq!(vec_norm(&[1.0, 2.0, 2.0]), 3.0);
        assert_eq!(vec_dist(&[0.0; 4], &[1.0; 4]), 2.0);
        assert_eq!(
            weighted_sum(&[vec![1.0], vec![3.0], vec![5.0]], &[1.0, 1.0, 1.0]),
            vec![9.0]
        );
    }

    #[test]
    #[should_panic(expected = "dimension mismatch")]
    fn mismatch_panics() {
        let _ = vec_add(&[1.0], &[1.0, 2.0]);
    }
}
