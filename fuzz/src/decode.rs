//! Fuzz bytes as a stream of bounded choices (arbitrary's [`Unstructured`]). An exhausted
//! input reads as the smallest choice, so every byte string, the empty one included, is a
//! valid case.

use arbitrary::Unstructured;

/// The choices of one input, read from the front.
pub(crate) struct Bytes<'a>(Unstructured<'a>);

impl<'a> Bytes<'a> {
    pub(crate) fn new(data: &'a [u8]) -> Self {
        Bytes(Unstructured::new(data))
    }

    /// An integer in `lo ..= hi`.
    pub(crate) fn int(&mut self, lo: i64, hi: i64) -> i64 {
        self.0.int_in_range(lo..=hi).unwrap_or(lo)
    }

    /// One of `n` choices, `0 .. n`.
    pub(crate) fn choice(&mut self, n: usize) -> usize {
        self.0.choose_index(n).unwrap_or(0)
    }

    /// `true` with probability about `1/n` on random bytes.
    pub(crate) fn one_in(&mut self, n: u32) -> bool {
        self.0.ratio(1, n).unwrap_or(false)
    }

    /// Any `f64`, NaN, infinities, subnormals and signed zeros included.
    pub(crate) fn raw(&mut self) -> f64 {
        f64::from_bits(self.0.arbitrary().unwrap_or(0))
    }

    /// `m·10^e` with `m` in `[1, 10)` (three digits) and `e` in `lo ..= hi`.
    pub(crate) fn magnitude(&mut self, lo: i32, hi: i32) -> f64 {
        let m = 1.0 + self.int(0, 899) as f64 / 100.0;
        let e = self.int(i64::from(lo), i64::from(hi));
        #[allow(clippy::cast_possible_truncation)]
        let e = e as i32;
        m * 10f64.powi(e)
    }

    /// A value that should be positive: mostly a magnitude `10^lo ..= 10^hi`, now and then
    /// any `f64` (the constructors and planners must reject the bad ones).
    pub(crate) fn positive(&mut self, lo: i32, hi: i32) -> f64 {
        if self.one_in(32) {
            self.raw()
        } else {
            self.magnitude(lo, hi)
        }
    }

    /// A coordinate: a multiple of `scale/4` in `±32·scale`, now and then any `f64`.
    pub(crate) fn coord(&mut self, scale: f64) -> f64 {
        if self.one_in(64) {
            self.raw()
        } else {
            self.int(-128, 128) as f64 * scale / 4.0
        }
    }

    /// A fraction in `[0, 1]` (1/1000 steps).
    pub(crate) fn unit(&mut self) -> f64 {
        self.int(0, 1000) as f64 / 1000.0
    }
}
