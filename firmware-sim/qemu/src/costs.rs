//! The instructions of a streaming loop's calls, counted when the loop is handed a
//! [`Costs`]: the dense polyline of [`streaming`](crate::streaming) and the G-code program
//! of [`gcode`](crate::gcode) count theirs through the same [`count`].
//!
//! The loops take `Option<&mut Costs<…>>`: without one they call their work directly and
//! keep no list; with one, each call is measured by the [`WideCounter`] (**instruction
//! counts, not cycles**, under QEMU `-icount`) and its count added to the total and, when
//! the loop says so, to the list of the calls that handed the stream a move or of the polls
//! that compiled ticks. The lists are bounded and live with the caller, outside the loop's
//! frame.

use heapless::Vec;

use crate::counter::{Calibration, WideCounter};

/// A counter, its calibration, and what a loop counted with them: the instructions of each
/// call that handed the stream a move, of each poll that compiled ticks, and of every call
/// counted.
///
/// A count that finds its list full is left out of it and counted in
/// [`unlisted`](Self::unlisted), so that a measurement can fail rather than report the
/// median of part of the calls.
pub struct Costs<'a, const M: usize, const P: usize> {
    counter: &'a WideCounter,
    cal: &'a Calibration,
    /// Each call that handed the stream a move (a push, a feed), in instructions.
    pub moves: Vec<u64, M>,
    /// Each poll that compiled ticks, in instructions.
    pub polls: Vec<u64, P>,
    /// Every call counted, in instructions.
    pub total: u64,
    /// Counts left out of a full list.
    pub unlisted: usize,
}

impl<'a, const M: usize, const P: usize> Costs<'a, M, P> {
    /// Empty lists, counted with `counter` and converted with `cal`.
    pub fn new(counter: &'a WideCounter, cal: &'a Calibration) -> Self {
        Costs {
            counter,
            cal,
            moves: Vec::new(),
            polls: Vec::new(),
            total: 0,
            unlisted: 0,
        }
    }

    /// Calls `f` and adds its instructions to the total; returns them with its result.
    pub fn count<R>(&mut self, f: impl FnOnce() -> R) -> (u64, R) {
        let (n, r) = self.counter.counts(f);
        let c = self.cal.instructions_wide(n);
        self.total += c;
        (c, r)
    }

    /// Lists `c` among the calls that handed the stream a move.
    pub fn list_move(&mut self, c: u64) {
        if self.moves.push(c).is_err() {
            self.unlisted += 1;
        }
    }

    /// Lists `c` among the polls that compiled ticks.
    pub fn list_poll(&mut self, c: u64) {
        if self.polls.push(c).is_err() {
            self.unlisted += 1;
        }
    }
}

/// Calls `f`; with `costs`, counts its instructions ([`Costs::count`]) and returns them with
/// its result, without, returns 0 with it.
pub fn count<R, const M: usize, const P: usize>(
    costs: Option<&mut Costs<'_, M, P>>,
    f: impl FnOnce() -> R,
) -> (u64, R) {
    match costs {
        Some(costs) => costs.count(f),
        None => (0, f()),
    }
}
