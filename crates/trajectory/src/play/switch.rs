//! The piece switch at full feed on the tick grid: the last tick of a piece outputs its
//! sample and loads the next piece's state in the same pass (the format's switch kernel),
//! inlined into [`Sampler::next`], [`Sampler::next_into`] and [`Sampler::next_position`] so
//! that it costs about as much as an ordinary tick.
//!
//! The next piece is the head of the pieces still to come ([`Sampler`]'s `pieces`, a slice
//! of the path in RAM), so that a switch is a pop from a slice: no index arithmetic, no
//! search. A blob's pieces come from its records, read in place (out of line: they are
//! decoded or loaded by the record kernels). After the last piece comes the path's end
//! state as a piece of one tick (the end sample); its tick, loading nothing new, finishes
//! the playback, and every further tick is the standstill.

use super::form::Rounded;
use super::{Kernel, Sampler, SamplerState};
use crate::path::Piece;
use crate::path::view::piece_record_len;
use crate::path::{AxisState, Sample};

/// What the inline piece switch does once the pieces to come are used up (or withheld).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum After {
    /// Loads the end state, a piece of one tick: the end sample (a path in RAM, on the tick
    /// grid).
    End,
    /// Finishes: the end state is loaded and its one tick is being played.
    Finish,
    /// Leaves the switch to [`Sampler::switch_other`]: a blob's records, or a switch off the
    /// tick grid.
    Other,
}

/// A switch the out-of-line piece switch makes ([`Sampler::switch_other`]).
enum Other<'a> {
    /// From a blob's record (its values); the number of the tick being played.
    Record(u64, &'a [u8]),
    /// Into the end state or at it (a blob's end); the number of the tick being played.
    End(u64),
    /// Off the tick grid: the tick is [`next_other`](Sampler::next_other)'s (a shifted load).
    Shifted,
}

impl<'a, N: Kernel, const A: usize> Sampler<'a, N, A> {
    /// The bookkeeping of a switch into a piece of `ticks` ticks (`left == 1`): returns the
    /// number of the tick being played.
    #[inline(always)]
    fn enter(&mut self, ticks: u32) -> u64 {
        // This tick is `end − 1`, the next one `end`, the new piece's last `end + ticks − 1`.
        let tick = self.end.wrapping_sub(1);
        self.end = self.end.wrapping_add(u64::from(ticks));
        self.left = ticks;
        self.chains = ticks;
        tick
    }

    /// The inline switch into the next piece of a path in RAM (`left == 1`, on the tick
    /// grid): takes the piece and enters it; returns the number of the tick being played and
    /// the piece, or `None` when no piece is left to the inline switch.
    #[inline(always)]
    pub(super) fn take_piece(&mut self) -> Option<(u64, &'a Piece<N, A>)> {
        let (p, rest) = self.pieces.split_first()?;
        self.pieces = rest;
        Some((self.enter(p.ticks), p))
    }

    /// The bookkeeping of a switch into the end sample: the end state as a piece of one
    /// tick. Returns the number of the tick being played.
    #[inline(always)]
    fn enter_end(&mut self) -> u64 {
        self.ended = true;
        self.after = After::Finish;
        self.enter(1)
    }

    /// The bookkeeping of the end sample's tick: finished (`left = 0`: every further tick
    /// is the standstill, off the fast path). Returns the number of the tick being played.
    #[inline(always)]
    fn finish(&mut self) -> u64 {
        self.left = 0;
        self.chains = 0;
        self.mode = SamplerState::Finished;
        self.end.wrapping_sub(1)
    }

    /// The bookkeeping of the inline switch once `pieces` is empty: the number of the tick
    /// being played, or `None` when the switch is [`switch_other`](Self::switch_other)'s.
    #[inline(always)]
    fn past_pieces(&mut self) -> Option<u64> {
        match self.after {
            After::End => Some(self.enter_end()),
            After::Finish => Some(self.finish()),
            After::Other => None,
        }
    }

    /// The end state, loaded by the switch past the last piece (at the end sample's own
    /// tick it is loaded again over itself, which leaves it unchanged).
    #[inline(always)]
    fn end_state(&self) -> &'a [AxisState<N>; A] {
        &self.path.header().end_state
    }

    /// The next blob record's length and values, taken from the records to come.
    fn pop_record(&mut self) -> Option<(u32, &'a [u8])> {
        let (record, rest) = self.records.split_at_checked(piece_record_len::<N>(A))?;
        self.records = rest;
        let (ticks, values) = record.split_at_checked(4)?;
        Some((u32::from_le_bytes(ticks.try_into().ok()?), values))
    }

    /// The bookkeeping of a switch that the inline switch leaves to the out-of-line ones: a
    /// blob's next record, or its end (on the tick grid), or off the grid a shifted load
    /// (the tick is then [`next_other`](Self::next_other)'s).
    #[inline(always)]
    fn switch_other(&mut self) -> Other<'a> {
        if !self.on_grid {
            return Other::Shifted;
        }
        if let Some((ticks, values)) = self.pop_record() {
            return Other::Record(self.enter(ticks), values);
        }
        self.records = &[];
        Other::End(if self.ended {
            self.finish()
        } else {
            self.enter_end()
        })
    }

    /// The piece switch of [`next`](Self::next) (`left == 1`, the chains caught up).
    #[inline(always)]
    pub(super) fn switch_sample(&mut self) -> Sample<N::Out, A> {
        if let Some((tick, p)) = self.take_piece() {
            return N::switch_sample(&mut self.state, &p.axes, tick);
        }
        let Some(tick) = self.past_pieces() else {
            return self.switch_other_sample();
        };
        let end = self.end_state();
        N::switch_sample(&mut self.state, end, tick)
    }

    /// [`switch_sample`](Self::switch_sample) from a blob's record, the end of a blob, or
    /// off the tick grid.
    #[inline(never)]
    fn switch_other_sample(&mut self) -> Sample<N::Out, A> {
        match self.switch_other() {
            Other::Record(tick, values) => N::switch_sample_bytes(&mut self.state, values, tick),
            Other::End(tick) => {
                let end = self.end_state();
                N::switch_sample(&mut self.state, end, tick)
            }
            Other::Shifted => self.next_other::<Rounded>(),
        }
    }

    /// The piece switch of [`next_into`](Self::next_into).
    #[inline(always)]
    pub(super) fn switch_native(&mut self, out: &mut Sample<N::Native, A>) {
        if let Some((tick, p)) = self.take_piece() {
            return N::switch_native(&mut self.state, &p.axes, tick, out);
        }
        let Some(tick) = self.past_pieces() else {
            return self.switch_other_native(out);
        };
        let end = self.end_state();
        N::switch_native(&mut self.state, end, tick, out);
    }

    /// [`switch_native`](Self::switch_native) from a blob's record, the end of a blob, or
    /// off the tick grid.
    #[inline(never)]
    fn switch_other_native(&mut self, out: &mut Sample<N::Native, A>) {
        match self.switch_other() {
            Other::Record(tick, values) => {
                N::switch_native_bytes(&mut self.state, values, tick, out);
            }
            Other::End(tick) => {
                let end = self.end_state();
                N::switch_native(&mut self.state, end, tick, out);
            }
            Other::Shifted => self.next_other_into(out),
        }
    }

    /// The piece switch of [`next_position`](Self::next_position): fresh chains are loaded,
    /// so the lagging ones need no catching up.
    #[inline(always)]
    pub(super) fn switch_position(&mut self) -> [N::Out; A] {
        if let Some((_, p)) = self.take_piece() {
            return N::switch_position(&mut self.state, &p.axes);
        }
        if self.past_pieces().is_none() {
            return self.switch_other_position();
        }
        let end = self.end_state();
        N::switch_position(&mut self.state, end)
    }

    /// [`switch_position`](Self::switch_position) from a blob's record, the end of a blob,
    /// or off the tick grid.
    #[inline(never)]
    fn switch_other_position(&mut self) -> [N::Out; A] {
        match self.switch_other() {
            Other::Record(_, values) => N::switch_position_bytes(&mut self.state, values),
            Other::End(_) => {
                let end = self.end_state();
                N::switch_position(&mut self.state, end)
            }
            Other::Shifted => self.next_other_position(),
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::compile::testing::{Quintic, helix};
    use crate::compile::{CompileOptions, compile};
    use crate::num::Q40;
    use crate::path::{Path, PathBlob, PathView};
    use crate::plan::Along;
    use strak_curves::Scalar;

    fn path<N: Kernel>() -> Path<N, 3, 512> {
        compile(
            &Along::new(&helix(2.0, 2.0, 1.0), &Quintic(0.5)),
            10_000.0,
            &CompileOptions::new().with_tolerance(1e-5),
        )
        .unwrap()
    }

    /// The index of the piece that holds tick `k` of `path` (the piece count from its end on).
    fn piece_at<N: Kernel>(path: &Path<N, 3, 512>, k: u32) -> usize {
        path.pieces()
            .iter()
            .position(|p| k < p.start() + p.ticks())
            .unwrap_or(path.pieces().len())
    }

    /// At full feed every tick of `view` is a fast tick or an inline switch (in RAM) or a
    /// record switch (a blob): after each, the current piece and the playback point are
    /// those of the next tick, the end sample is a piece of one tick, and its own tick
    /// finishes.
    fn switches_at_full_feed<N: Kernel>(path: &Path<N, 3, 512>, view: PathView<'_, N, 3>) {
        let mut s = Sampler::new(view);
        let ticks = path.ticks();
        for k in 0..ticks {
            assert_eq!(s.piece(), piece_at(path, k), "tick {k}");
            assert_eq!(s.progress(), f64::from(k), "tick {k}");
            s.next_position();
        }
        // the end sample: the end state loaded, one tick long
        assert!(s.ended && s.left == 1 && !s.is_finished());
        assert_eq!(s.piece(), path.pieces().len());
        assert_eq!(s.state, path.header.end_state);
        let end = s.next();
        assert_eq!(
            (end.tick, end.position),
            (u64::from(ticks), path.end_position())
        );
        assert_eq!(end.velocity, path.end_velocity());
        assert!(s.is_finished() && s.left == 0);
        // the standstill
        let after = s.next();
        assert_eq!(
            (after.tick, after.position),
            (u64::from(ticks) + 1, end.position)
        );
        assert!(after.velocity.iter().all(|v| Scalar::to_f64(*v) == 0.0));
    }

    fn full_feed<N: Kernel>() {
        let path = path::<N>();
        assert!(path.pieces().len() > 20);
        switches_at_full_feed(&path, path.view());
        let mut bytes = std::vec![0_u8; path.blob_len()];
        path.to_bytes(&mut bytes).unwrap();
        let blob = PathBlob::<N, 3>::from_bytes(&bytes).unwrap();
        switches_at_full_feed(&path, blob.view());
    }

    #[test]
    fn every_switch_at_full_feed_takes_the_next_piece_in_order() {
        full_feed::<f32>();
        full_feed::<f64>();
        full_feed::<Q40>();
    }

    /// Off the tick grid (full feed again at a fractional offset) the inline switch gets no
    /// pieces: they are withheld at their place (the current piece is still known), and
    /// every switch is the shifted load of `next_other`; the end is still exact.
    fn off_the_grid<N: Kernel>() {
        let path = path::<N>();
        let mut s = Sampler::new(&path);
        for _ in 0..200 {
            s.next();
        }
        assert_eq!(s.after, After::End);
        assert!(!s.pieces.is_empty());
        s.set_feed(0.3);
        for _ in 0..300 {
            s.next();
        }
        s.set_feed(1.0);
        for _ in 0..2000 {
            if s.feed.is_idle() && s.theta == N::ZERO {
                break;
            }
            s.next();
        }
        assert!(!s.on_grid);
        let mut switches = 0;
        let mut last = s.next();
        while !s.is_finished() {
            assert!(s.pieces.is_empty() && s.after == After::Other);
            let (piece, progress) = (s.piece(), s.progress());
            if let Some(p) = path.pieces().get(piece) {
                let (start, end) = (f64::from(p.start()), f64::from(p.start() + p.ticks()));
                assert!(
                    start <= progress && progress < end,
                    "{progress} in piece {piece}"
                );
            }
            last = s.next();
            switches += usize::from(s.piece() != piece);
        }
        assert_eq!(last.position, path.end_position());
        assert!(switches > 10, "{switches}");
    }

    #[test]
    fn off_the_tick_grid_the_pieces_are_withheld_from_the_inline_switch() {
        off_the_grid::<f32>();
        off_the_grid::<f64>();
        off_the_grid::<Q40>();
    }
}
