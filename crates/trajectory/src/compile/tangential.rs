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
    /// The last `CELLS + 1` cells, a ring; `recent` is the newest.
    cells: [Cell; CELLS + 1],
    recent: usize,
    /// How many cells have been added (saturating).
    added: usize,
    /// The bound so far, in units per tick².
    peak: f64,
}

impl Tangential {
    /// No pieces yet.
    pub(super) fn new() -> Self {
        Tangential {
            cells: [Cell::default(); CELLS + 1],
            recent: 0,
            added: 0,
            peak: 0.0,
        }
    }

    /// Adds the next piece `p(i) = a + b i + c i² + d i³` per axis (`i` in ticks, `0 ≤ i ≤
    /// n`).
    pub(super) fn piece<const A: usize>(&mut self, coeffs: &[[f64; 4]; A], n: u32) {
        let norm = |f: &dyn Fn(&[f64; 4]) -> f64| {
            libm::sqrt(coeffs.iter().map(|c| f(c) * f(c)).sum::<f64>())
        };
        let speed = |i: f64| norm(&|&[_, b, c, d]| b + i * (2.0 * c + 3.0 * d * i));
        let acceleration = |i: f64| norm(&|&[_, _, c, d]| 2.0 * c + 6.0 * d * i);
        let (turns, count) = super::peaks::speed_turns(coeffs, f64::from(n));
        let turns = turns.get(..count).unwrap_or(&[]);
        #[allow(clippy::cast_precision_loss)]
        let step = 1.0 / CELLS as f64;
        let (mut left, mut s_left, mut a_left) = (0.0, speed(0.0), acceleration(0.0));
        for j in 1..=n.saturating_mul(CELLS as u32) {
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
            self.add(cell);
            (left, s_left, a_left) = (right, s_right, a_right);
        }
    }

    /// The bound over the pieces so far, in units/s² at tick period `period`.
    pub(super) fn peak(&self, period: f64) -> f64 {
        self.peak / (period * period)
    }

    /// Adds a cell and pairs it with the `CELLS` before it (and itself).
    fn add(&mut self, cell: Cell) {
        self.recent = (self.recent + 1) % self.cells.len();
        if let Some(slot) = self.cells.get_mut(self.recent) {
            *slot = cell;
        }
        self.added = self.added.saturating_add(1);
        let mut acceleration = 0.0_f64;
        for k in 0..self.added.min(self.cells.len()) {
            let index = (self.recent + self.cells.len() - k) % self.cells.len();
            let Some(start) = self.cells.get(index) else {
                continue;
            };
            acceleration = acceleration.max(start.acceleration);
            #[allow(clippy::cast_precision_loss)]
            let window = (((k + 1) as f64) / CELLS as f64).min(1.0);
            let change = (cell.hi - start.lo).max(start.hi - cell.lo);
            let bound = window * change.min(window * acceleration);
            // `max` keeps a NaN out; the compile's check rejects non-finite peaks elsewhere.
            self.peak = self.peak.max(bound);
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
}
