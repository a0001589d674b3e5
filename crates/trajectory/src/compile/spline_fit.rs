//! The C² cubic spline in time with knots on the tick grid, clamped at both ends, refined by
//! adaptive knot insertion (the complete cubic spline interpolant in Hermite form, with the
//! knot slopes as unknowns: de Boor, *A Practical Guide to Splines*, ch. IV).
//!
//! The spline interpolates the exact positions `y_j = x(k_j)` at the knot ticks `k_j`; its
//! slopes `s_j` (units per tick) solve the tridiagonal system of C² continuity at the inner
//! knots,
//!
//! `h_j·s_{j−1} + 2(h_{j−1} + h_j)·s_j + h_{j−1}·s_{j+1} = 3(h_j·δ_{j−1} + h_{j−1}·δ_j)`,
//!
//! with `h_j = k_{j+1} − k_j` and `δ_j = (y_{j+1} − y_j)/h_j`, and the end slopes given
//! (clamped spline). The system is strictly diagonally dominant, so the Thomas algorithm
//! (elimination without pivoting, `O(m)`) is stable; its pivots are at least
//! `h_{j−1} + h_j ≥ 2`.
//!
//! A fit may also clamp the second derivative at either end (a stretch of a motion whose
//! ends are known to the acceleration, so that it joins its neighbours in position, slope
//! and acceleration). The knot next to a clamped end then is not interpolated but follows
//! from the slopes. At the start, the first piece's second derivative at 0 is
//! `2(3δ₀ − 2s₀ − s₁)/h₀ = α`, so
//!
//! `y₁ = Y + (h₀/3)·s₁`,  `Y = y₀ + h₀·(α·h₀/2 + 2s₀)/3`,
//!
//! and substituting it into the first two rows changes the first diagonal to
//! `2h₀ + h₁ + h₀²/h₁` and the second row's sub-diagonal to `h₂·(1 + h₀/h₁)` (their right
//! sides take `Y` for `y₁`). The elimination stays stable: the first multiplier is
//! `c₀ = h₀/(2h₀ + h₁ + h₀²/h₁)`, so the second pivot is
//! `2(h₁ + h₂) − h₂·h₀/(h₀ + h₁) > 2h₁ + h₂`, and the rows after it are unchanged. The end
//! is the mirror image: `y_{m−1} = Y′ − (h_{m−1}/3)·s_{m−1}` with
//! `Y′ = y_m − h_{m−1}·(2s_m − β·h_{m−1}/2)/3`, the last diagonal
//! `h_{m−2} + 2h_{m−1} + h_{m−1}²/h_{m−2}` and the super-diagonal of the row before it
//! `h_{m−3}·(1 + h_{m−1}/h_{m−2})`; the last pivots of the elimination stay positive as
//! the rows before them are dominant. A free knot's position is checked against the
//! tolerance like the ticks inside a piece, and a fit with both ends clamped has at least
//! three pieces, so that the two free knots differ.

use super::knots::Knots;
use crate::error::Error;

/// A clamped cubic spline on the tick grid with up to `K::capacity()` pieces and `A` axes,
/// in `f64`, its knots kept in `K` ([`PieceKnots`](super::knots::PieceKnots): the pieces of
/// the path being compiled).
///
/// Knot `j` (`0 ..= m`) is at tick `knot(j)`; knot 0 is tick 0 and kept here; the knots
/// `1 ..= m` are kept in `K`, so nothing is sized `capacity + 1`. `E` holds the clamped
/// end accelerations: [`Unclamped`] (nothing, for a fit of a whole motion) or
/// [`Clamped`].
pub(crate) struct SplineFit<const A: usize, K, E = Unclamped> {
    /// Number of pieces `m` (1 ..= capacity).
    m: usize,
    /// Knot `j + 1` in slot `j`: its tick, position, slope (units/tick; slot `m − 1` holds
    /// the clamped end), the Thomas algorithm's modified super-diagonal, the split mark of
    /// the piece ending there.
    knots: K,
    start_value: [f64; A],
    start_slope: [f64; A],
    end_slope: [f64; A],
    ends: E,
}

/// What a fit keeps of the second derivatives clamped at its ends (`end` 0 is the start,
/// 1 the end).
pub(crate) trait EndClamps<const A: usize> {
    /// Nothing clamped.
    fn none() -> Self;
    /// The clamped second derivative (units/tick²) at `end`, if any.
    fn acceleration(&self, end: usize) -> Option<[f64; A]>;
    /// The position of the free knot next to `end` (knot 1 or knot `m − 1`).
    fn free_value(&self, end: usize) -> [f64; A];
    /// Sets the position of the free knot next to `end`.
    fn set_free_value(&mut self, end: usize, value: [f64; A]);
}

/// No clamped ends, and no room for them.
pub(crate) struct Unclamped;

impl<const A: usize> EndClamps<A> for Unclamped {
    fn none() -> Self {
        Unclamped
    }
    fn acceleration(&self, _: usize) -> Option<[f64; A]> {
        None
    }
    fn free_value(&self, _: usize) -> [f64; A] {
        [0.0; A] // never read: without a clamp no knot is free
    }
    fn set_free_value(&mut self, _: usize, _: [f64; A]) {}
}

/// Clamped end accelerations, and the positions of the knots they free.
pub(crate) struct Clamped<const A: usize> {
    /// The clamped second derivatives (units/tick²) at the start and the end, if any.
    accelerations: [Option<[f64; A]>; 2],
    /// With a clamped acceleration: the positions of knot 1 and knot `m − 1` (from the
    /// slopes, see the module docs), in place of the stored ones.
    free_values: [[f64; A]; 2],
}

impl<const A: usize> EndClamps<A> for Clamped<A> {
    fn none() -> Self {
        Clamped {
            accelerations: [None; 2],
            free_values: [[0.0; A]; 2],
        }
    }
    fn acceleration(&self, end: usize) -> Option<[f64; A]> {
        self.accelerations[end]
    }
    fn free_value(&self, end: usize) -> [f64; A] {
        self.free_values[end]
    }
    fn set_free_value(&mut self, end: usize, value: [f64; A]) {
        self.free_values[end] = value;
    }
}

/// The local tick offsets at which a piece of `n` ticks is checked: the quarter points
/// `n/4, n/2, 3n/4` rounded, without duplicates and without the (exact) end points.
pub(crate) fn check_points(n: u32) -> impl Iterator<Item = u32> {
    let at = move |q: u32| ((u64::from(n) * u64::from(q) + 2) / 4) as u32;
    let (a, b, c) = (at(1), at(2), at(3));
    [
        Some(a),
        (b != a).then_some(b),
        (c != b && c != a).then_some(c),
    ]
    .into_iter()
    .flatten()
    .filter(move |&i| i > 0 && i < n)
}

/// The polynomial coefficients `(a, b, c, d)` of `p(i) = a + b i + c i² + d i³` on `[0, n]`
/// from Hermite data: end values `y0, y1`, end slopes `s0, s1` (per tick).
pub(crate) fn hermite_coefficients(y0: f64, y1: f64, s0: f64, s1: f64, n: f64) -> [f64; 4] {
    let delta = (y1 - y0) / n;
    let c = (3.0 * delta - 2.0 * s0 - s1) / n;
    let d = (s0 + s1 - 2.0 * delta) / (n * n);
    [y0, s0, c, d]
}

impl<const A: usize, K: Knots<A>, E: EndClamps<A>> SplineFit<A, K, E> {
    /// A spline without knots over the storage `knots`; [`SplineFit::init`] lays out its
    /// grid.
    pub(crate) fn empty(knots: K) -> Self {
        SplineFit {
            m: 0,
            knots,
            start_value: [0.0; A],
            start_slope: [0.0; A],
            end_slope: [0.0; A],
            ends: E::none(),
        }
    }

    /// Whether knot 1 (`end = 0`) or knot `m − 1` (`end = 1`) has a free position.
    fn free_knot(&self, end: usize) -> bool {
        let clamped = |e: usize| self.ends.acceleration(e).is_some();
        let needed = 1 + usize::from(clamped(0)) + usize::from(clamped(1));
        clamped(end) && self.m >= needed
    }

    /// The spline on a uniform initial grid: `⌈ticks / max_len⌉` pieces of at most `max_len`
    /// ticks, with the positions from `exact`.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the grid needs more pieces than `knots` holds; errors
    /// of `exact`.
    #[cfg(test)]
    pub(crate) fn new(
        knots: K,
        ticks: u32,
        max_len: u32,
        start_slope: [f64; A],
        end_slope: [f64; A],
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<Self, Error> {
        let mut fit = Self::empty(knots);
        fit.init(ticks, max_len, start_slope, end_slope, exact)?;
        Ok(fit)
    }

    /// The storage's capacity error for `required` pieces, if it has less room.
    fn room(&self, required: usize) -> Result<(), Error> {
        let capacity = self.knots.capacity();
        if required > capacity {
            Err(Error::CapacityExceeded { capacity, required })
        } else {
            Ok(())
        }
    }

    /// Sets the number of pieces (making room in the storage).
    fn set_pieces(&mut self, m: usize) {
        self.knots.set_len(m);
        self.m = m;
    }

    /// Lays out the uniform initial grid of [`SplineFit::new`] in place, over whatever the
    /// spline holds.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the grid needs more pieces than the storage holds;
    /// errors of `exact`.
    pub(crate) fn init(
        &mut self,
        ticks: u32,
        max_len: u32,
        start_slope: [f64; A],
        end_slope: [f64; A],
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        let m = ticks.div_ceil(max_len.max(1)).max(1) as usize;
        self.room(m)?;
        self.set_pieces(m);
        self.start_value = exact(0)?;
        self.start_slope = start_slope;
        self.end_slope = end_slope;
        for j in 0..m {
            // ⌊(j+1)·N/m⌋: strictly increasing (N ≥ m), steps of at most ⌈N/m⌉ ≤ max_len.
            #[allow(clippy::cast_possible_truncation)]
            let k = ((j as u64 + 1) * u64::from(ticks) / m as u64) as u32;
            self.knots.set_end(j, k);
            self.knots.set_value(j, exact(k)?);
            self.knots.set_split(j, false);
        }
        Ok(())
    }

    /// Inserts a knot at tick `k` with the position from `exact`, unless `k` is already a
    /// knot or not strictly inside `(0, ticks)` (then nothing changes). Keeps the knots
    /// sorted (`O(m)` shifting); the slopes are solved later.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the storage holds no further piece; errors of `exact`.
    pub(crate) fn insert_knot(
        &mut self,
        k: u32,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        let m = self.m;
        let last = self.knot(m);
        // The first slot whose tick is ≥ k (binary search).
        let (mut lo, mut hi) = (0, m);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.knots.end(mid) < k {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        let at = lo;
        if k == 0 || k >= last || (at < m && self.knots.end(at) == k) {
            return Ok(());
        }
        self.room(m + 1)?;
        let value = exact(k)?;
        self.set_pieces(m + 1);
        for i in (at..m).rev() {
            self.knots.set_end(i + 1, self.knots.end(i));
            self.knots.set_value(i + 1, self.knots.value(i));
            self.knots.set_split(i + 1, false);
        }
        self.knots.set_end(at, k);
        self.knots.set_value(at, value);
        self.knots.set_split(at, false);
        Ok(())
    }

    /// Splits every piece longer than `max_len` ticks into `⌈n / max_len⌉` pieces of equal
    /// length (within a tick), keeping the existing knots.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the result would not fit the storage; errors of `exact`.
    pub(crate) fn subdivide(
        &mut self,
        max_len: u32,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        let max_len = max_len.max(1);
        let parts = |n: u32| n.div_ceil(max_len).max(1) as usize;
        let m: usize = (0..self.m)
            .map(|j| parts(self.knot(j + 1) - self.knot(j)))
            .sum();
        self.room(m)?;
        let old = self.m;
        self.set_pieces(m);
        // Backwards, so that every entry is read before its slot is overwritten.
        let mut w = m;
        for j in (0..old).rev() {
            let (k0, k1) = (self.knot(j), self.knots.end(j));
            let value = self.knots.value(j);
            let q = parts(k1 - k0);
            w -= 1;
            self.knots.set_end(w, k1);
            self.knots.set_value(w, value);
            self.knots.set_split(w, false);
            for i in (1..q).rev() {
                #[allow(clippy::cast_possible_truncation)]
                let k = k0 + (u64::from(k1 - k0) * i as u64 / q as u64) as u32;
                w -= 1;
                self.knots.set_end(w, k);
                self.knots.set_value(w, exact(k)?);
                self.knots.set_split(w, false);
            }
        }
        Ok(())
    }

    /// The number of pieces.
    pub(crate) fn pieces(&self) -> usize {
        self.m
    }

    /// The tick of knot `j` (`0 ..= m`).
    pub(crate) fn knot(&self, j: usize) -> u32 {
        match j.checked_sub(1) {
            None => 0,
            Some(i) => self.knots.end(i),
        }
    }

    /// The position at knot `j`.
    pub(crate) fn value(&self, j: usize) -> [f64; A] {
        match j.checked_sub(1) {
            None => self.start_value,
            Some(0) if self.free_knot(0) => self.ends.free_value(0),
            Some(i) if i + 2 == self.m && self.free_knot(1) => self.ends.free_value(1),
            Some(i) => self.knots.value(i),
        }
    }

    /// The slope (units/tick) at knot `j`.
    pub(crate) fn slope(&self, j: usize) -> [f64; A] {
        match j.checked_sub(1) {
            None => self.start_slope,
            Some(i) if i + 1 == self.m => self.end_slope,
            Some(i) => self.knots.slope(i),
        }
    }

    /// Solves for the inner knot slopes (Thomas algorithm, `O(m)`).
    pub(crate) fn solve(&mut self) {
        let m = self.m;
        if m >= 1 {
            self.knots.set_slope(m - 1, self.end_slope);
        }
        if m < 2 {
            return;
        }
        // With clamped accelerations the free knots take `Y`, `Y′` while the rows are built.
        let (free_start, free_end) = (self.free_knot(0), self.free_knot(1));
        let h = |j: usize| f64::from(self.knot(j + 1) - self.knot(j));
        let (h0, h1) = (h(0), h(1));
        let (hl, hp) = (h(m - 1), h(m - 2));
        if let (true, Some(alpha)) = (free_start, self.ends.acceleration(0)) {
            let y = core::array::from_fn(|a| {
                self.start_value[a] + h0 * (alpha[a] * h0 / 2.0 + 2.0 * self.start_slope[a]) / 3.0
            });
            self.ends.set_free_value(0, y);
        }
        if let (true, Some(beta)) = (free_end, self.ends.acceleration(1)) {
            let end = self.knots.value(m - 1);
            let y = core::array::from_fn(|a| {
                end[a] - hl * (2.0 * self.end_slope[a] - beta[a] * hl / 2.0) / 3.0
            });
            self.ends.set_free_value(1, y);
        }
        // Rows r = 0 ..= m−2 for the inner knots j = r + 1.
        let mut prev_c = 0.0;
        let mut prev_d = [0.0; A];
        for r in 0..m - 1 {
            let j = r + 1;
            let h_prev = f64::from(self.knot(j) - self.knot(j - 1));
            let h_next = f64::from(self.knot(j + 1) - self.knot(j));
            let (y_prev, y, y_next) = (self.value(j - 1), self.value(j), self.value(j + 1));
            let (mut sub, mut diag, mut sup) = (h_next, 2.0 * (h_prev + h_next), h_prev);
            if free_start && r == 0 {
                diag += h0 * h0 / h1 - h1;
            }
            if free_start && r == 1 {
                sub *= 1.0 + h0 / h1;
            }
            if free_end && r + 2 == m {
                diag += hl * hl / hp - hp;
            }
            if free_end && r + 3 == m {
                sup *= 1.0 + hl / hp;
            }
            let mut rhs = [0.0; A];
            for a in 0..A {
                let d_prev = (y[a] - y_prev[a]) / h_prev;
                let d_next = (y_next[a] - y[a]) / h_next;
                rhs[a] = 3.0 * (h_next * d_prev + h_prev * d_next);
                if r == 0 {
                    rhs[a] -= sub * self.start_slope[a];
                }
                if r == m - 2 {
                    rhs[a] -= sup * self.end_slope[a];
                }
            }
            let (sub_eff, c_prev) = if r == 0 { (0.0, 0.0) } else { (sub, prev_c) };
            let pivot = diag - sub_eff * c_prev;
            let c = sup / pivot;
            let mut d = [0.0; A];
            for a in 0..A {
                d[a] = (rhs[a] - sub_eff * prev_d[a]) / pivot;
            }
            self.knots.set_scratch(r, c);
            self.knots.set_slope(r, d);
            prev_c = c;
            prev_d = d;
        }
        // Back substitution; the row m−2 is complete.
        for r in (0..m - 2).rev() {
            let c = self.knots.scratch(r);
            let next = self.knots.slope(r + 1);
            let mut slope = self.knots.slope(r);
            for (x, n) in slope.iter_mut().zip(next) {
                *x -= c * n;
            }
            self.knots.set_slope(r, slope);
        }
        if free_start {
            let (y, s1) = (self.ends.free_value(0), self.knots.slope(0));
            self.ends
                .set_free_value(0, core::array::from_fn(|a| y[a] + h0 / 3.0 * s1[a]));
        }
        if free_end {
            let (y, s) = (self.ends.free_value(1), self.knots.slope(m - 2));
            self.ends
                .set_free_value(1, core::array::from_fn(|a| y[a] - hl / 3.0 * s[a]));
        }
    }

    /// The coefficients `(a, b, c, d)` per axis of piece `j` and its length in ticks.
    pub(crate) fn piece(&self, j: usize) -> ([[f64; 4]; A], u32) {
        let n = self.knot(j + 1) - self.knot(j);
        let (y0, y1, s0, s1) = (
            self.value(j),
            self.value(j + 1),
            self.slope(j),
            self.slope(j + 1),
        );
        let nf = f64::from(n);
        let coeffs = core::array::from_fn(|a| hermite_coefficients(y0[a], y1[a], s0[a], s1[a], nf));
        (coeffs, n)
    }

    /// Calls `f` with the coefficients `(a, b, c, d)` per axis and the length in ticks of
    /// every piece in order, as [`piece`](Self::piece) gives them (each knot read once).
    pub(crate) fn each_piece(&self, mut f: impl FnMut([[f64; 4]; A], u32)) {
        let (mut k0, mut y0, mut s0) = (0, self.value(0), self.slope(0));
        for j in 0..self.m {
            let (k1, y1, s1) = (self.knot(j + 1), self.value(j + 1), self.slope(j + 1));
            let nf = f64::from(k1 - k0);
            f(
                core::array::from_fn(|a| hermite_coefficients(y0[a], y1[a], s0[a], s1[a], nf)),
                k1 - k0,
            );
            (k0, y0, s0) = (k1, y1, s1);
        }
    }

    /// Checks every piece at its quarter points against `exact`; marks the pieces whose error
    /// exceeds `tol` on some axis and returns how many.
    pub(crate) fn mark(
        &mut self,
        tol: f64,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<usize, Error> {
        self.mark_at(tol, exact, false)
    }

    /// [`mark`](Self::mark) at every inner tick of every piece instead of its quarter points.
    fn mark_every_tick(
        &mut self,
        tol: f64,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<usize, Error> {
        self.mark_at(tol, exact, true)
    }

    /// Marks the pieces whose error at the quarter points (or at every inner tick) exceeds
    /// `tol` on some axis; returns how many.
    fn mark_at(
        &mut self,
        tol: f64,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
        every_tick: bool,
    ) -> Result<usize, Error> {
        let mut count = 0;
        for j in 0..self.m {
            let (coeffs, n) = self.piece(j);
            let k0 = self.knot(j);
            let mut bad = false;
            let (mut quarters, mut ticks) = (check_points(n), 1..n);
            let points: &mut dyn Iterator<Item = u32> = if every_tick {
                &mut ticks
            } else {
                &mut quarters
            };
            // a free knot's position is checked like an inner tick
            let free_start = (j == 0 && self.free_knot(0)).then_some(n);
            let free_end = (j + 1 == self.m && self.free_knot(1)).then_some(0);
            for i in points.chain(free_start).chain(free_end) {
                let want = exact(k0 + i)?;
                let x = f64::from(i);
                for (c, w) in coeffs.iter().zip(want) {
                    let p = c[0] + x * (c[1] + x * (c[2] + x * c[3]));
                    // NaN (a bad time law) counts as a failure, too.
                    let err = (p - w).abs();
                    if err > tol || err.is_nan() {
                        bad = true;
                    }
                }
                if bad {
                    break;
                }
            }
            self.knots.set_split(j, bad);
            count += usize::from(bad);
        }
        Ok(count)
    }

    /// Splits every marked piece at its middle tick (`count` pieces are marked).
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the result would not fit the storage; errors of `exact`.
    pub(crate) fn split_marked(
        &mut self,
        count: usize,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        let m = self.m + count;
        self.room(m)?;
        let old = self.m;
        self.set_pieces(m);
        // Backwards, so that every entry is read before its slot is overwritten: piece j is
        // written at slot ≥ j, its start knot (slot j − 1) is still unread.
        let mut w = m;
        for j in (0..old).rev() {
            let (end, value, split) = (self.knots.end(j), self.knots.value(j), self.knots.split(j));
            w -= 1;
            self.knots.set_end(w, end);
            self.knots.set_value(w, value);
            self.knots.set_split(w, false);
            if split {
                let k0 = self.knot(j);
                let mid = k0 + (end - k0) / 2;
                w -= 1;
                self.knots.set_end(w, mid);
                self.knots.set_value(w, exact(mid)?);
                self.knots.set_split(w, false);
            }
        }
        Ok(())
    }

    /// Fits: solve, check, split, until every piece passes (each round adds at least one
    /// piece, so this ends after at most `capacity` rounds).
    pub(crate) fn refine(
        &mut self,
        tol: f64,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        loop {
            self.solve();
            let count = self.mark(tol, exact)?;
            if count == 0 {
                return Ok(());
            }
            self.split_marked(count, exact)?;
        }
    }

    /// Fits until every tick is within `tol` of `exact`: [`refine`](Self::refine) at the
    /// quarter points against `quarter_tol ≤ tol` (cheap, and enough where the motion is
    /// smooth: the error between two knots is then dominated by the bump
    /// `∝ (i − k_j)²(k_{j+1} − i)²`), then every inner tick against `tol` (a time law need
    /// not be smooth between the knots: acceleration steps, features shorter than a
    /// piece); the pieces that fail are split and both checks run again. Ends after at
    /// most `capacity` splits.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the pieces do not fit the storage; errors of `exact`.
    pub(crate) fn refine_every_tick(
        &mut self,
        quarter_tol: f64,
        tol: f64,
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        loop {
            self.refine(quarter_tol, exact)?;
            let count = self.mark_every_tick(tol, exact)?;
            if count == 0 {
                return Ok(());
            }
            self.split_marked(count, exact)?;
        }
    }

    /// Hands every piece in order to `write` (the storage, the piece's index `j`, its
    /// coefficients per axis, its first tick and its length), consuming the fit: the knot
    /// data of slot `j` is read before `write` is called for piece `j`, so `write` may
    /// overwrite slot `j` with the piece (the pieces of [`PieceKnots`](super::knots::PieceKnots)
    /// become the path's).
    ///
    /// # Errors
    /// The first error of `write`.
    pub(crate) fn write_pieces(
        mut self,
        mut write: impl FnMut(&mut K, usize, [[f64; 4]; A], u32, u32) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let (mut k0, mut y0, mut s0) = (0, self.start_value, self.start_slope);
        for j in 0..self.m {
            let (k1, y1, s1) = (self.knot(j + 1), self.value(j + 1), self.slope(j + 1));
            let n = k1 - k0;
            let nf = f64::from(n);
            let coeffs =
                core::array::from_fn(|a| hermite_coefficients(y0[a], y1[a], s0[a], s1[a], nf));
            write(&mut self.knots, j, coeffs, k0, n)?;
            (k0, y0, s0) = (k1, y1, s1);
        }
        Ok(())
    }
}

impl<const A: usize, K: Knots<A>> SplineFit<A, K, Clamped<A>> {
    /// Clamps the second derivatives (units/tick²) at the start and at the end to the given
    /// values, where given (module docs). Splits the pieces at their middle ticks until
    /// there are enough for the clamps (two, three for both).
    ///
    /// # Errors
    /// [`Error::EmptyPath`] for a fit with too few ticks for the clamps (two, three for
    /// both); [`Error::CapacityExceeded`] when the storage holds too few pieces; errors of
    /// `exact`.
    pub(crate) fn clamp_accelerations(
        &mut self,
        accelerations: [Option<[f64; A]>; 2],
        exact: &mut impl FnMut(u32) -> Result<[f64; A], Error>,
    ) -> Result<(), Error> {
        let needed = 1 + accelerations.iter().flatten().count();
        let ticks = self.knot(self.m);
        if (ticks as usize) < needed {
            return Err(Error::EmptyPath);
        }
        while self.m < needed {
            let widest = (0..self.m)
                .max_by_key(|&j| self.knot(j + 1) - self.knot(j))
                .unwrap_or(0);
            let mid = self.knot(widest) + (self.knot(widest + 1) - self.knot(widest)) / 2;
            self.insert_knot(mid, exact)?;
        }
        self.ends.accelerations = accelerations;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::compile::knots::ArrayKnots;
    use std::vec::Vec;

    #[test]
    fn quarter_points() {
        let pts = |n| check_points(n).collect::<Vec<_>>();
        assert!(pts(1).is_empty());
        assert_eq!(pts(2), [1]);
        assert_eq!(pts(3), [1, 2]);
        assert_eq!(pts(4), [1, 2, 3]);
        assert_eq!(pts(256), [64, 128, 192]);
        assert_eq!(pts(7), [2, 4, 5]);
    }

    #[test]
    fn hermite_coefficients_match_the_data() {
        let [a, b, c, d] = hermite_coefficients(1.0, 3.0, 0.5, -0.25, 4.0);
        let p = |x: f64| a + b * x + c * x * x + d * x * x * x;
        let dp = |x: f64| b + 2.0 * c * x + 3.0 * d * x * x;
        assert_eq!(p(0.0), 1.0);
        assert!((p(4.0) - 3.0).abs() < 1e-14);
        assert_eq!(dp(0.0), 0.5);
        assert!((dp(4.0) + 0.25).abs() < 1e-14);
    }

    /// A cubic in t is reproduced exactly by the clamped spline, whatever the knots.
    #[test]
    fn clamped_spline_reproduces_a_cubic() {
        let x = |k: f64| 2.0 - 0.3 * k + 0.01 * k * k - 2e-5 * k * k * k;
        let dx = |k: f64| -0.3 + 0.02 * k - 6e-5 * k * k;
        let mut exact = |k: u32| Ok([x(f64::from(k)), -x(f64::from(k))]);
        let mut fit: SplineFit<2, ArrayKnots<2, 16>> = SplineFit::new(
            ArrayKnots::new(),
            1000,
            90,
            [dx(0.0), -dx(0.0)],
            [dx(1000.0), -dx(1000.0)],
            &mut exact,
        )
        .unwrap();
        assert_eq!(fit.pieces(), 12);
        fit.solve();
        for j in 0..=fit.pieces() {
            let k = f64::from(fit.knot(j));
            let s = fit.slope(j);
            assert!((s[0] - dx(k)).abs() < 1e-12, "knot {j}");
            assert!((s[1] + dx(k)).abs() < 1e-12);
        }
        // pieces are at most 90 ticks, the grid is uniform within one tick
        for j in 0..fit.pieces() {
            let n = fit.knot(j + 1) - fit.knot(j);
            assert!(n == 83 || n == 84, "{n}");
        }
        assert_eq!(fit.mark(1e-9, &mut exact).unwrap(), 0);
    }

    /// The natural-spline system's known answer: for y = k² on knots 0, 1, 2 with clamped
    /// slopes 0 and 4 the inner slope is 2.
    #[test]
    fn three_knot_system() {
        let mut exact = |k: u32| Ok([f64::from(k * k)]);
        let mut fit: SplineFit<1, ArrayKnots<1, 4>> =
            SplineFit::new(ArrayKnots::new(), 2, 1, [0.0], [4.0], &mut exact).unwrap();
        fit.solve();
        assert_eq!(fit.slope(1), [2.0]);
    }

    #[test]
    fn refinement_splits_where_needed_and_meets_the_tolerance() {
        // A step-like function: only the pieces near k = 500 need refining.
        let f = |k: f64| libm::tanh((k - 500.0) / 20.0);
        let mut exact = |k: u32| Ok([f(f64::from(k))]);
        let mut fit: SplineFit<1, ArrayKnots<1, 256>> =
            SplineFit::new(ArrayKnots::new(), 1000, 256, [0.0], [0.0], &mut exact).unwrap();
        fit.refine(1e-6, &mut exact).unwrap();
        let mut short = 0;
        assert!(fit.pieces() > 50);
        for j in 0..fit.pieces() {
            let (c, n) = fit.piece(j);
            let k0 = fit.knot(j);
            for i in 0..=n {
                let x = f64::from(i);
                let p = c[0][0] + x * (c[0][1] + x * (c[0][2] + x * c[0][3]));
                // checked at the quarter points against tol; every tick within 2·tol
                assert!(
                    (p - f(f64::from(k0 + i))).abs() <= 2e-6,
                    "piece {j} tick {i}"
                );
            }
            short += usize::from(n < 64);
        }
        assert!(short > 4, "refined near the step");
        // short pieces at the step (≈ 2 ticks), long ones where the function is flat
        let len = |j: usize| fit.knot(j + 1) - fit.knot(j);
        let at_step = (0..fit.pieces()).find(|&j| fit.knot(j + 1) > 500).unwrap();
        assert!(len(at_step) <= 2);
        assert!(len(0) >= 16 && len(fit.pieces() - 1) >= 16);
        assert!(fit.pieces() < 160, "{}", fit.pieces());
    }

    #[test]
    fn knots_are_inserted_in_order() {
        let mut exact = |k: u32| Ok([f64::from(k) * 0.5]);
        let mut fit: SplineFit<1, ArrayKnots<1, 6>> =
            SplineFit::new(ArrayKnots::new(), 1000, 256, [0.5], [0.5], &mut exact).unwrap();
        assert_eq!(fit.pieces(), 4); // knots 0, 250, 500, 750, 1000
        for k in [0, 1000, 2000, 250, 600, 10, 600] {
            fit.insert_knot(k, &mut exact).unwrap();
        }
        let knots: Vec<u32> = (0..=fit.pieces()).map(|j| fit.knot(j)).collect();
        assert_eq!(knots, [0, 10, 250, 500, 600, 750, 1000]);
        assert_eq!(fit.value(4), [300.0]);
        assert_eq!(fit.value(6), [500.0]);
        assert_eq!(
            fit.insert_knot(900, &mut exact),
            Err(Error::CapacityExceeded {
                capacity: 6,
                required: 7
            })
        );
        // an existing knot needs no room
        assert_eq!(fit.insert_knot(750, &mut exact), Ok(()));
        // a straight line stays exact
        fit.solve();
        assert_eq!(fit.mark(1e-12, &mut exact).unwrap(), 0);
    }

    #[test]
    fn subdivision_keeps_the_knots() {
        let mut exact = |k: u32| Ok([f64::from(k)]);
        let mut fit: SplineFit<1, ArrayKnots<1, 16>> =
            SplineFit::new(ArrayKnots::new(), 1000, 1000, [1.0], [1.0], &mut exact).unwrap();
        fit.insert_knot(150, &mut exact).unwrap();
        fit.subdivide(100, &mut exact).unwrap();
        let knots: Vec<u32> = (0..=fit.pieces()).map(|j| fit.knot(j)).collect();
        assert_eq!(
            knots,
            [0, 75, 150, 244, 338, 433, 527, 622, 716, 811, 905, 1000]
        );
        assert!((0..=fit.pieces()).all(|j| fit.value(j) == [f64::from(fit.knot(j))]));
        let mut small: SplineFit<1, ArrayKnots<1, 3>> =
            SplineFit::new(ArrayKnots::new(), 1000, 1000, [1.0], [1.0], &mut exact).unwrap();
        assert_eq!(
            small.subdivide(256, &mut exact),
            Err(Error::CapacityExceeded {
                capacity: 3,
                required: 4
            })
        );
    }

    /// The second derivative (per tick²) of piece `j` at its start and at its end.
    fn second_derivatives<const A: usize, K: Knots<A>, E: EndClamps<A>>(
        fit: &SplineFit<A, K, E>,
        j: usize,
    ) -> [[f64; 2]; A] {
        let (coeffs, n) = fit.piece(j);
        let n = f64::from(n);
        coeffs.map(|[_, _, c, d]| [2.0 * c, 2.0 * c + 6.0 * d * n])
    }

    /// The clamps of the start, the end and both.
    const CLAMPS: [[bool; 2]; 3] = [[true, false], [false, true], [true, true]];

    /// A cubic with its own accelerations clamped is reproduced exactly, the free knots
    /// included.
    #[test]
    fn clamped_accelerations_reproduce_a_cubic() {
        let x = |k: f64| 2.0 - 0.3 * k + 0.01 * k * k - 2e-5 * k * k * k;
        let dx = |k: f64| -0.3 + 0.02 * k - 6e-5 * k * k;
        let ddx = |k: f64| 0.02 - 1.2e-4 * k;
        for [start, end] in CLAMPS {
            let mut exact = |k: u32| Ok([x(f64::from(k))]);
            let mut fit: SplineFit<1, ArrayKnots<1, 16>, Clamped<1>> = SplineFit::new(
                ArrayKnots::new(),
                1000,
                90,
                [dx(0.0)],
                [dx(1000.0)],
                &mut exact,
            )
            .unwrap();
            let clamps = [start.then_some([ddx(0.0)]), end.then_some([ddx(1000.0)])];
            fit.clamp_accelerations(clamps, &mut exact).unwrap();
            fit.solve();
            for j in 0..=fit.pieces() {
                let k = f64::from(fit.knot(j));
                assert!(
                    (fit.value(j)[0] - x(k)).abs() < 1e-11,
                    "{start} {end}: value {j}"
                );
                assert!(
                    (fit.slope(j)[0] - dx(k)).abs() < 1e-12,
                    "{start} {end}: slope {j}"
                );
            }
            assert_eq!(fit.mark(1e-9, &mut exact).unwrap(), 0);
        }
    }

    /// Clamped accelerations off the function's by what a neighbouring fit's end
    /// acceleration is off (tolerance / piece²) are met exactly, the fit is C² at every
    /// knot, and every tick (the free knots included) lies within the tolerance after
    /// refinement; a single piece is split for the clamps.
    #[test]
    fn clamped_accelerations_are_met_within_the_tolerance() {
        let f = |k: f64| 3.0 * libm::sin(k / 150.0 + 0.3);
        let ddf = |k: f64| -3.0 * libm::sin(k / 150.0 + 0.3) / (150.0 * 150.0);
        let slope = |k: f64| libm::cos(k / 150.0 + 0.3) / 50.0;
        let mut exact = |k: u32| Ok([f(f64::from(k)), -2.0 * f(f64::from(k))]);
        for [start, end] in CLAMPS {
            for offset in [0.0, 1e-8, -5e-8] {
                let accel =
                    |k: f64, on: bool| on.then_some([ddf(k) + offset, -2.0 * (ddf(k) + offset)]);
                let clamps = [accel(0.0, start), accel(700.0, end)];
                let mut fit: SplineFit<2, ArrayKnots<2, 128>, Clamped<2>> = SplineFit::new(
                    ArrayKnots::new(),
                    700,
                    1000,
                    [slope(0.0), -2.0 * slope(0.0)],
                    [slope(700.0), -2.0 * slope(700.0)],
                    &mut exact,
                )
                .unwrap();
                fit.clamp_accelerations(clamps, &mut exact).unwrap();
                assert_eq!(fit.pieces(), 1 + usize::from(start) + usize::from(end));
                fit.subdivide(64, &mut exact).unwrap();
                fit.refine_every_tick(0.5e-6, 1e-6, &mut exact).unwrap();
                let last = fit.pieces() - 1;
                for (clamp, got) in clamps.iter().zip([
                    second_derivatives(&fit, 0).map(|d| d[0]),
                    second_derivatives(&fit, last).map(|d| d[1]),
                ]) {
                    if let Some(want) = clamp {
                        for a in 0..2 {
                            assert!(
                                (got[a] - want[a]).abs() < 1e-15,
                                "{start} {end} {offset}: {got:?}"
                            );
                        }
                    }
                }
                for j in 1..fit.pieces() {
                    let (before, after) =
                        (second_derivatives(&fit, j - 1), second_derivatives(&fit, j));
                    for a in 0..2 {
                        assert!((before[a][1] - after[a][0]).abs() < 1e-15, "knot {j}");
                    }
                }
                for j in 0..fit.pieces() {
                    let (c, n) = fit.piece(j);
                    for i in 0..=n {
                        let t = f64::from(i);
                        let want = exact(fit.knot(j) + i).unwrap();
                        for a in 0..2 {
                            let p = c[a][0] + t * (c[a][1] + t * (c[a][2] + t * c[a][3]));
                            assert!(
                                (p - want[a]).abs() <= 1e-6,
                                "{start} {end} {offset}: piece {j} tick {i}"
                            );
                        }
                    }
                }
            }
        }
        let mut line = |k: u32| Ok([f64::from(k)]);
        let mut short: SplineFit<1, ArrayKnots<1, 4>, Clamped<1>> =
            SplineFit::new(ArrayKnots::new(), 2, 2, [1.0], [1.0], &mut line).unwrap();
        assert_eq!(
            short.clamp_accelerations([Some([0.0]), Some([0.0])], &mut line),
            Err(Error::EmptyPath)
        );
        assert_eq!(
            short.clamp_accelerations([Some([0.0]), None], &mut line),
            Ok(())
        );
    }

    #[test]
    fn capacity_is_reported() {
        let mut exact = |k: u32| Ok([f64::from(k)]);
        let fit = SplineFit::<1, _>::new(
            ArrayKnots::<1, 3>::new(),
            1000,
            256,
            [1.0],
            [1.0],
            &mut exact,
        );
        assert_eq!(
            fit.err(),
            Some(Error::CapacityExceeded {
                capacity: 3,
                required: 4
            })
        );
        let f = |k: f64| libm::sin(k / 10.0);
        let mut exact = |k: u32| Ok([f(f64::from(k))]);
        let mut fit = SplineFit::<1, _>::new(
            ArrayKnots::<1, 8>::new(),
            1000,
            256,
            [0.1],
            [0.1 * libm::cos(100.0)],
            &mut exact,
        )
        .unwrap();
        assert!(matches!(
            fit.refine(1e-9, &mut exact),
            Err(Error::CapacityExceeded { capacity: 8, .. })
        ));
    }
}
