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

use super::{Kernel, Sampler, SamplerState};
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

    /// `true` when [`switch_other`](Self::switch_other) loads a blob's record or the end
    /// state (on the tick grid); `false` when the tick is
    /// [`next_other`](Self::next_other)'s (a shifted load). Takes the record.
    #[inline(always)]
    fn switch_other(&mut self) -> Option<Result<(u64, &'a [u8]), u64>> {
        if !self.on_grid {
            return None;
        }
        Some(match self.pop_record() {
            Some((ticks, values)) => Ok((self.enter(ticks), values)),
            None => {
                self.records = &[];
                Err(if self.ended {
                    self.finish()
                } else {
                    self.enter_end()
                })
            }
        })
    }

    /// The piece switch of [`next`](Self::next) (`left == 1`, the chains caught up).
    #[inline(always)]
    pub(super) fn switch_sample(&mut self) -> Sample<N::Out, A> {
        if let Some((p, rest)) = self.pieces.split_first() {
            self.pieces = rest;
            let tick = self.enter(p.ticks);
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
            Some(Ok((tick, values))) => N::switch_sample_bytes(&mut self.state, values, tick),
            Some(Err(tick)) => {
                let end = self.end_state();
                N::switch_sample(&mut self.state, end, tick)
            }
            None => self.next_other::<super::form::Rounded>(),
        }
    }

    /// The piece switch of [`next_into`](Self::next_into).
    #[inline(always)]
    pub(super) fn switch_native(&mut self, out: &mut Sample<N::Native, A>) {
        if let Some((p, rest)) = self.pieces.split_first() {
            self.pieces = rest;
            let tick = self.enter(p.ticks);
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
            Some(Ok((tick, values))) => N::switch_native_bytes(&mut self.state, values, tick, out),
            Some(Err(tick)) => {
                let end = self.end_state();
                N::switch_native(&mut self.state, end, tick, out);
            }
            None => self.next_other_into(out),
        }
    }

    /// The piece switch of [`next_position`](Self::next_position): fresh chains are loaded,
    /// so the lagging ones need no catching up.
    #[inline(always)]
    pub(super) fn switch_position(&mut self) -> [N::Out; A] {
        if let Some((p, rest)) = self.pieces.split_first() {
            self.pieces = rest;
            self.enter(p.ticks);
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
            Some(Ok((_, values))) => N::switch_position_bytes(&mut self.state, values),
            Some(Err(_)) => {
                let end = self.end_state();
                N::switch_position(&mut self.state, end)
            }
            None => self.next_other_position(),
        }
    }
}
