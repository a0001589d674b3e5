//! Factorial and binomial coefficient (seeds/000, "Fakultät", "Binomialkoeffizient").

/// The factorial `n! = n · (n−1) · … · 2 · 1` (with `0! = 1`), computed as an `f64` product
/// (seeds/000). Exact for `n ≤ 18`; beyond that rounded like any `f64` product.
///
/// ```
/// assert_eq!(strak_ref::factorial(0), 1.0);
/// assert_eq!(strak_ref::factorial(5), 120.0);
/// ```
pub fn factorial(n: u32) -> f64 {
    let mut f = 1.0;
    for j in 2..=n {
        f *= f64::from(j);
    }
    f
}

/// The binomial coefficient `C(n, k) = n! / (k! (n−k)!)` via factorials exactly as in
/// seeds/000; `0` when `k > n`.
///
/// ```
/// assert_eq!(strak_ref::binomial(4, 2), 6.0);
/// assert_eq!(strak_ref::binomial(3, 4), 0.0);
/// ```
pub fn binomial(n: u32, k: u32) -> f64 {
    if k > n {
        return 0.0;
    }
    factorial(n) / (factorial(k) * factorial(n - k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factorials() {
        assert_eq!(factorial(1), 1.0);
        assert_eq!(factorial(3), 6.0);
        assert_eq!(factorial(10), 3_628_800.0);
    }

    #[test]
    fn pascal_triangle_rows_of_seed() {
        // seeds/000: Pascal's triangle n = 0..4.
        let rows: [&[f64]; 5] = [
            &[1.0],
            &[1.0, 1.0],
            &[1.0, 2.0, 1.0],
            &[1.0, 3.0, 3.0, 1.0],
            &[1.0, 4.0, 6.0, 4.0, 1.0],
        ];
        for (n, row) in rows.iter().enumerate() {
            for (k, &c) in row.iter().enumerate() {
                assert_eq!(binomial(n as u32, k as u32), c);
            }
        }
    }

    #[test]
    fn pascal_rule() {
        for n in 1..15u32 {
            for k in 1..n {
                assert_eq!(binomial(n, k), binomial(n - 1, k - 1) + binomial(n - 1, k));
            }
        }
    }
}
