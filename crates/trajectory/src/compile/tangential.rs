//! A bound of the tangential acceleration `d|ẋ|/dt` as playback samples it, at any feed.
//!
//! At feed `φ ≤ 1` two consecutive samples are `φ·ẋ` at path times `s` and `s + φ` (in
//! ticks), so the measured tangential acceleration is `φ·(S(s + φ) − S(s))/T²`, with
//! `S = |ẋ|` the speed per tick. At feed 1 after a feed change, `s` need not be a whole
//! tick, and at a lower feed the window `φ` is shorter than a tick: where the speed dips
//! within a tick (a compiled corner, cut within the tolerance), the means over whole ticks
//! miss the dip, and a feed hold samples it.
//!
//! The bound covers every window `0 < φ ≤ 1` at every phase `s`. The path is cut into
//! cells of `1/m` tick, `m` = [`CELLS`]. On each cell the extremes `Lo`, `Hi` of `S` are
//! exact: `S²` is a quartic per piece, largest and smallest at a cell's ends or at a root
//! of `d|ẋ|²/di` inside it. A window starting in cell `a` and ending in cell `b = a + k`
//! (`k ≤ m`) has `φ ≤ φₖ = min(1, (k + 1)/m)` and
//! `|S(s + φ) − S(s)| ≤ min(max(Hi_b − Lo_a, Hi_a − Lo_b), φₖ·A)`, where `A` is the
//! largest `|ẍ|` over the cells `a … b` (`|dS/di| = |ẋ·ẍ|/|ẋ| ≤ |ẍ|`, and `ẍ` is affine in
//! a piece, so its norm is largest at a cell's end). The bound is the largest
//! `φₖ·min(…)` over all pairs of cells; along a straight ramp (`|ẍ| = dS/di`) it is exact,
//! elsewhere it exceeds the true largest value by at most about `1/m` of it.
//!
//! A feed that changes within the tick adds `(φ₂ − φ₁)·S(s)`: the feed ramp's own
//! tangential acceleration, which the feed share reserves.

/// Cells per tick.
pub(super) const CELLS: usize = 16;

/// `φₖ = min(1, (k + 1)/m)` for `k = 0 … m`: the longest window from a cell to the `k`-th
/// after it.
const WINDOWS: [f64; CELLS + 1] = {
    let mut w = [1.0; CELLS + 1];
    let mut k = 0;
    while k < CELLS {
        #[allow(clippy::cast_precision_loss)]
        let share = (k + 1) as f64 / CELLS as f64;
        w[k] = share;
        k += 1;
    }
    w
};

/// The extremes of one cell, in ticks: the lowest and highest speed `|ẋ|` and the largest
/// `|ẍ|`.
#[derive(Clone, Copy, Debug, Default)]
struct Cell {
    lo: f64,
    hi: f64,
    acceleration: f64,
}

/// The bound of the module's docs over a path's pieces, given in order
/// ([`Tangential::piece`]); cells of adjacent pieces pair like any others.
#[derive(Debug)]
pub(super) struct Tangential {
    /// The last `CELLS + 1` cells, a ring; `newest` is the last added.
    cells: [Cell; CELLS + 1],
    newest: usize,
    /// How many cells have been added (saturating).
    added: usize,
    /// The largest `|ẍ|` of the previous piece (per tick²).
    previous: f64,
    /// The bound so far, in units per tick².
    peak: f64,
}

impl Tangential {
    /// No pieces yet.
    pub(super) fn new() -> Self {
        Tangential {
            cells: [Cell::default(); CELLS + 1],
            newest: 0,
            added: 0,
            previous: 0.0,
            peak: 0.0,
        }
    }

    /// Adds the next piece `p(i) = a + b i + c i² + d i³` per axis (`i` in ticks, `0 ≤ i ≤
    /// n`).
    ///
    /// No window touching the piece can show more than the largest `|ẍ|` of the piece and
    /// of the one before (each window's bound is at most `φₖ²·A`), so when that is within
    /// the bound so far, only the piece's last tick of cells is stored, for the next
    /// piece's windows.
    pub(super) fn piece<const A: usize>(&mut self, coeffs: &[[f64; 4]; A], n: u32) {
        let norm = |f: &dyn Fn(&[f64; 4]) -> f64| {
            libm::sqrt(coeffs.iter().map(|c| f(c) * f(c)).sum::<f64>())
        };
        let speed = |i: f64| norm(&|&[_, b, c, d]| b + i * (2.0 * c + 3.0 * d * i));
        let acceleration = |i: f64| norm(&|&[_, _, c, d]| 2.0 * c + 6.0 * d * i);
        let largest = acceleration(0.0).max(acceleration(f64::from(n)));
        let pair = largest.max(self.previous) > self.peak || largest.is_nan();
        self.previous = largest;
        let (turns, count) = super::peaks::speed_turns(coeffs, f64::from(n));
        let turns = turns.get(..count).unwrap_or(&[]);
        #[allow(clippy::cast_precision_loss)]
        let step = 1.0 / CELLS as f64;
        let cells = n.saturating_mul(CELLS as u32);
        let first = if pair { 0 } else { n.saturating_sub(1) };
        let mut left = f64::from(first);
        let (mut s_left, mut a_left) = (speed(left), acceleration(left));
        for j in first.saturating_mul(CELLS as u32) + 1..=cells {
            let right = f64::from(j) * step;
            let (s_right, a_right) = (speed(right), acceleration(right));
            let mut cell = Cell {
                lo: s_left.min(s_right),
                hi: s_left.max(s_right),
                acceleration: a_left.max(a_right),
            };
            for &t in turns.iter().filter(|&&t| t > left && t < right) {
                let s = speed(t);
                cell.lo = cell.lo.min(s);
                cell.hi = cell.hi.max(s);
            }
            self.add(cell, pair);
            (left, s_left, a_left) = (right, s_right, a_right);
        }
    }

    /// The bound over the pieces so far, in units/s² at tick period `period`.
    pub(super) fn peak(&self, period: f64) -> f64 {
        self.peak / (period * period)
    }

    /// Adds a cell and, when `pair`, pairs it with the `CELLS` before it (and itself).
    fn add(&mut self, cell: Cell, pair: bool) {
        self.newest = if self.newest == CELLS {
            0
        } else {
            self.newest + 1
        };
        if let Some(slot) = self.cells.get_mut(self.newest) {
            *slot = cell;
        }
        self.added = self.added.saturating_add(1);
        if !pair {
            return;
        }
        let (mut acceleration, mut index) = (0.0_f64, self.newest);
        for &window in WINDOWS.iter().take(self.added) {
            let Some(start) = self.cells.get(index) else {
                break;
            };
            acceleration = acceleration.max(start.acceleration);
            let change = (cell.hi - start.lo).max(start.hi - cell.lo);
            // `max` keeps a NaN out; the compile's check rejects non-finite peaks elsewhere.
            self.peak = self.peak.max(window * change.min(window * acceleration));
            index = if index == 0 { CELLS } else { index - 1 };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The speed per tick of a piece at `i`.
    fn speed<const A: usize>(coeffs: &[[f64; 4]; A], i: f64) -> f64 {
        coeffs
            .iter()
            .map(|&[_, b, c, d]| {
                let v = b + i * (2.0 * c + 3.0 * d * i);
                v * v
            })
            .sum::<f64>()
            .sqrt()
    }

    /// The largest `φ·|S(s + φ) − S(s)|` of a speed `S` over `[0, n]` ticks on a grid of
    /// `steps` per tick in the phase `s` and the window `φ ≤ 1` (the measured quantity of
    /// the module's docs, sampled), per tick².
    fn sampled(speed: &dyn Fn(f64) -> f64, n: u32, steps: u32) -> f64 {
        let h = 1.0 / f64::from(steps);
        let mut best = 0.0_f64;
        for j in 0..n * steps {
            let s = f64::from(j) * h;
            for k in 1..=steps.min(n * steps - j) {
                let phi = f64::from(k) * h;
                best = best.max(phi * (speed(s + phi) - speed(s)).abs());
            }
        }
        best
    }

    fn bound<const A: usize>(coeffs: &[[f64; 4]; A], n: u32) -> f64 {
        let mut t = Tangential::new();
        t.piece(coeffs, n);
        t.peak(1.0)
    }

    #[test]
    fn a_straight_ramp_is_exact() {
        // x = a·i²/2: S = a·i, dS/di = a = |ẍ| on every window; the bound is a at φ = 1
        let a = 0.02;
        let ramp = [[0.0, 0.0, 0.5 * a, 0.0], [0.0, 0.0, 0.0, 0.0]];
        let b = bound(&ramp, 10);
        assert!((b - a).abs() <= 1e-15, "{b} {a}");
        let mut t = Tangential::new();
        t.piece(&ramp, 10);
        assert!((t.peak(1e-3) - a * 1e6).abs() <= 1e-9, "{}", t.peak(1e-3));
    }

    #[test]
    fn a_corner_within_a_tick_is_bounded_from_above() {
        // the velocity turns by 90° within one tick (x slows, y speeds up): the speed dips
        // to about 1/√2 inside it, while whole ticks see a small change
        let corner = [[0.0, 1.0, 0.0, -1.0 / 3.0], [0.0, 0.0, 0.0, 1.0 / 3.0]];
        let s = |i: f64| speed(&corner, i);
        let truth = sampled(&s, 1, 512);
        let whole_ticks = sampled(&s, 1, 1);
        let b = bound(&corner, 1);
        assert!(b >= truth, "{b} < {truth}");
        assert!(b <= truth * 1.15, "{b} > 1.15·{truth}");
        assert!(truth > 3.0 * whole_ticks, "{truth} {whole_ticks}");
    }

    #[test]
    fn windows_straddle_the_pieces() {
        // ẋ = i² then 1 + 2i − i² (one tick each, C¹): a window of one tick across the
        // join sees S rise by 1.5, either piece alone by 1
        let first = [[0.0, 0.0, 0.0, 1.0 / 3.0]];
        let second = [[1.0 / 3.0, 1.0, 1.0, -1.0 / 3.0]];
        let mut t = Tangential::new();
        t.piece(&first, 1);
        let alone = t.peak(1.0);
        assert!((1.0..1.1).contains(&alone), "{alone}");
        t.piece(&second, 1);
        let s = |i: f64| {
            if i <= 1.0 {
                speed(&first, i)
            } else {
                speed(&second, i - 1.0)
            }
        };
        let truth = sampled(&s, 2, 256);
        assert!((truth - 1.5).abs() < 1e-9, "{truth}");
        let both = t.peak(1.0);
        assert!(both >= truth && both <= 1.1 * truth, "{both} {truth}");
    }

    #[test]
    fn random_joined_pieces_are_bounded_from_above() {
        // pieces of 1 to 3 ticks in 2-D, each starting with the velocity the one before
        // ended with, against the sampled windows over the whole sequence
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut random = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            #[allow(clippy::cast_precision_loss)]
            let unit = (seed >> 11) as f64 / (1u64 << 53) as f64;
            2.0 * unit - 1.0
        };
        for _ in 0..20 {
            let mut pieces = [([[0.0; 4]; 2], 1_u32); 6];
            let mut v = [random(), random()];
            for slot in &mut pieces {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let n = 1 + (random().abs() * 3.0) as u32;
                let piece: [[f64; 4]; 2] =
                    core::array::from_fn(|axis| [0.0, v[axis], 0.3 * random(), 0.1 * random()]);
                let m = f64::from(n);
                v = core::array::from_fn(|axis| {
                    let [_, b, c, d] = piece[axis];
                    b + m * (2.0 * c + 3.0 * d * m)
                });
                *slot = (piece, n);
            }
            let mut t = Tangential::new();
            for (piece, n) in &pieces {
                t.piece(piece, *n);
            }
            let s = |mut i: f64| {
                for (piece, n) in &pieces {
                    let m = f64::from(*n);
                    if i <= m {
                        return speed(piece, i);
                    }
                    i -= m;
                }
                let (piece, n) = &pieces[5];
                speed(piece, f64::from(*n))
            };
            let ticks = pieces.iter().map(|p| p.1).sum();
            let truth = sampled(&s, ticks, 64);
            let b = t.peak(1.0);
            assert!(b >= truth, "{b} < {truth}");
            assert!(b <= 1.3 * truth, "{b} > 1.3·{truth}");
        }
    }
}
