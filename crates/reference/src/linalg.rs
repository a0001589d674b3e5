//! Small dense linear algebra: Gaussian elimination with partial pivoting, matrix inverse,
//! products and transpose. Matrices are `Vec<Vec<f64>>` in row-major order (`a[row][col]`).

/// Solves the square system `A x = b` by Gaussian elimination with partial pivoting (row swaps
/// choosing the largest remaining pivot magnitude in each column), then back substitution.
///
/// Returns `None` if `A` is not square, `b` has the wrong length, a pivot is exactly zero
/// (singular matrix), or the solution is not finite. Nearly singular systems are *not* detected
/// beyond that; they give inaccurate results, as in any textbook elimination.
///
/// ```
/// let x = strak_ref::solve_dense(vec![vec![2.0, 1.0], vec![1.0, 3.0]], vec![3.0, 5.0]).unwrap();
/// assert!((x[0] - 0.8).abs() < 1e-15 && (x[1] - 1.4).abs() < 1e-15);
/// assert!(strak_ref::solve_dense(vec![vec![1.0, 2.0], vec![2.0, 4.0]], vec![1.0, 1.0]).is_none());
/// ```
pub fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = a.len();
    if b.len() != n || a.iter().any(|row| row.len() != n) {
        return None;
    }
    // Forward elimination.
    for col in 0..n {
        // Partial pivoting: the row (at or below `col`) with the largest |a[row][col]|.
        let mut piv = col;
        for row in col + 1..n {
            if a[row][col].abs() > a[piv][col].abs() {
                piv = row;
            }
        }
        if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for row in col + 1..n {
            let factor = a[row][col] / a[col][col];
            if factor != 0.0 {
                for j in col..n {
                    a[row][j] -= factor * a[col][j];
                }
                b[row] -= factor * b[col];
            }
        }
    }
    // Back substitution.
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let mut s = b[row];
        for j in row + 1..n {
            s -= a[row][j] * x[j];
        }
        x[row] = s / a[row][row];
    }
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

/// The inverse `A⁻¹` of a square matrix, column by column: column `j` of `A⁻¹` solves
/// `A x = e_j` with [`solve_dense`]. `None` if `A` is not square or singular.
///
/// ```
/// let inv = strak_ref::invert(&[vec![2.0, 0.0], vec![0.0, 4.0]]).unwrap();
/// assert_eq!(inv, vec![vec![0.5, 0.0], vec![0.0, 0.25]]);
/// ```
pub fn invert(a: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    let mut inv = vec![vec![0.0; n]; n];
    for j in 0..n {
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        let col = solve_dense(a.to_vec(), e)?;
        for i in 0..n {
            inv[i][j] = col[i];
        }
    }
    Some(inv)
}

/// The transpose `Aᵀ` of a (possibly rectangular, non-empty-row) matrix.
///
/// ```
/// let t = strak_ref::transpose(&[vec![1.0, 2.0, 3.0]]);
/// assert_eq!(t, vec![vec![1.0], vec![2.0], vec![3.0]]);
/// ```
pub fn transpose(a: &[Vec<f64>]) -> Vec<Vec<f64>> {
    if a.is_empty() {
        return Vec::new();
    }
    let cols = a[0].len();
    (0..cols)
        .map(|j| a.iter().map(|row| row[j]).collect())
        .collect()
}

/// The matrix product `A B`.
///
/// # Panics
/// If the inner dimensions differ.
///
/// ```
/// let p = strak_ref::mat_mul(&[vec![1.0, 2.0]], &[vec![3.0], vec![4.0]]);
/// assert_eq!(p, vec![vec![11.0]]);
/// ```
pub fn mat_mul(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let inner = b.len();
    let cols = if inner == 0 { 0 } else { b[0].len() };
    a.iter()
        .map(|row| {
            assert_eq!(row.len(), inner, "mat_mul: inner dimension mismatch");
            (0..cols)
                .map(|j| (0..inner).map(|k| row[k] * b[k][j]).sum())
                .collect()
        })
        .collect()
}

/// The matrix-vector product `A x`.
///
/// # Panics
/// If a row of `A` and `x` differ in length.
///
/// ```
/// assert_eq!(strak_ref::mat_vec(&[vec![1.0, 2.0], vec![0.0, 1.0]], &[1.0, 1.0]), vec![3.0, 1.0]);
/// ```
pub fn mat_vec(a: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    a.iter()
        .map(|row| {
            assert_eq!(row.len(), x.len(), "mat_vec: dimension mismatch");
            row.iter().zip(x).map(|(r, v)| r * v).sum()
        })
        .collect()
}

/// The `n × n` identity matrix.
///
/// ```
/// assert_eq!(strak_ref::identity(2), vec![vec![1.0, 0.0], vec![0.0, 1.0]]);
/// ```
pub fn identity(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_system_needing_pivoting() {
        // a[0][0] = 0 forces a row swap.
        let a = vec![
            vec![0.0, 2.0, 1.0],
            vec![1.0, 1.0, 1.0],
            vec![2.0, 1.0, 3.0],
        ];
        let x_true = [1.0, -2.0, 3.0];
        let b = mat_vec(&a, &x_true);
        let x = solve_dense(a, b).unwrap();
        for i in 0..3 {
            assert!((x[i] - x_true[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn singular_and_malformed_give_none() {
        assert!(solve_dense(vec![vec![0.0, 0.0], vec![0.0, 1.0]], vec![1.0, 1.0]).is_none());
        assert!(solve_dense(vec![vec![1.0, 2.0]], vec![1.0]).is_none());
        assert!(solve_dense(vec![vec![1.0]], vec![1.0, 2.0]).is_none());
        assert!(invert(&[vec![1.0, 1.0], vec![1.0, 1.0]]).is_none());
    }

    #[test]
    fn inverse_times_matrix_is_identity() {
        let a = vec![
            vec![4.0, -2.0, 1.0, 0.5],
            vec![3.0, 6.0, -4.0, 2.0],
            vec![2.0, 1.0, 8.0, -1.0],
            vec![1.0, 1.0, 1.0, 1.0],
        ];
        let inv = invert(&a).unwrap();
        let p = mat_mul(&a, &inv);
        let id = identity(4);
        for i in 0..4 {
            for j in 0..4 {
                assert!((p[i][j] - id[i][j]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn transpose_twice_is_identity_map() {
        let a = vec![vec![1.0, 2.0, 3.0], vec![4.0, 5.0, 6.0]];
        assert_eq!(transpose(&transpose(&a)), a);
        assert_eq!(transpose(&a)[2], vec![3.0, 6.0]);
    }
}
