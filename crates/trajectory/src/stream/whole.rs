//! A whole curve planned and compiled into a [`Path`] by the stream: the curve is pushed as
//! one move and the stream's pieces are collected in the path, so that planning a path
//! needs the stream's window and the path's pieces, nothing of the size of the curve.

use heapless::Vec;

use super::moves::{Move, StreamCurve};
use super::queue::{PieceQueue, STRETCH_PIECES, Stream, StreamOptions};
use crate::compile::seal_streamed;
use crate::error::Error;
use crate::num::Number;
use crate::path::{Path, Piece};
use crate::plan::Limits;

/// Polls in a row that compile nothing before the window is taken to be too small to go on.
const MAX_STALLS: u32 = 4;

/// The pieces of a path as the queue a stream compiles into.
struct PathPieces<'p, N, const A: usize, const P: usize>(&'p mut Vec<Piece<N, A>, P>);

impl<N, const A: usize, const P: usize> PieceQueue<N, A> for PathPieces<'_, N, A, P> {
    fn room(&self) -> usize {
        P - self.0.len()
    }
    fn push_piece(&mut self, piece: Piece<N, A>) {
        let _ = self.0.push(piece);
    }
}

/// Plans the motion along `curve` from rest to rest under the machine's `limits` and
/// compiles it into `path` at the options' control rate, in the number format `N`, in
/// place: the stream's planner fed with the curve as one move ([`Move::curve`]), using
/// `stream` (reset here) as its working memory. The motion is the one a
/// [`StreamSampler`](crate::StreamSampler) plays when the same curve is streamed, piece for
/// piece; the path plays it with a [`Sampler`](crate::Sampler), with the feed ramps and the
/// events of any path, and serializes as a blob.
///
/// Where the stream's window (`Q` segments, `Z` zones) holds less than the braking distance
/// from the speed limit, the motion is slower than a plan of the whole curve at once
/// ([`PathTiming::plan`](crate::PathTiming::plan)), since it must always be able to come to
/// rest at the end of what the window holds. The path's
/// [`tolerance`](crate::PathHeader::tolerance) is the options' fit tolerance, its peaks are
/// read from its pieces, and its feed ramps keep to the limits with the options' feed
/// share, as a compiled path's do.
///
/// `path` must hold the pieces and [`STRETCH_PIECES`] more, the
/// most one stretch of the stream writes at once.
///
/// # Errors
/// The errors of [`Stream::reset`], [`Stream::push`] (a curve move that does not fit the
/// window: [`Error::ZoneCapacityExceeded`]) and [`Stream::poll`];
/// [`Error::CapacityExceeded`] when the pieces do not fit `path`;
/// [`Error::FeedReserveExceeded`] when the pieces use more than the promised share of a
/// limit. On an error `path` is empty.
///
/// ```
/// use strak_curves::{BSpline, ParamCurve};
/// use strak_trajectory::{
///     Limits, Path, Sampler, Stream, StreamOptions, plan_path_into,
/// };
/// let points = [[0.0, 0.0], [20.0, 0.0], [20.0, 20.0], [40.0, 20.0], [40.0, 0.0]];
/// let curve = BSpline::<[f64; 2], 5, 9>::clamped_uniform(3, &points, 0.0, 1.0)?;
/// let limits = Limits::new(100.0, 1_000.0, 20_000.0)?;
/// let mut stream = Box::new(Stream::<2, 8, 64, &BSpline<[f64; 2], 5, 9>>::unset());
/// let mut path = Box::new(Path::<f32, 2, 512>::new());
/// plan_path_into(&curve, limits, StreamOptions::new(1_000.0), &mut stream, &mut path)?;
/// let end = curve.eval(1.0).map(|x| x as f32); // the curve's end, [40, 0] within 10⁻¹³
/// assert_eq!(path.end_position(), end);
/// assert!(path.peak_velocity() <= 100.0);
/// let mut sampler = Sampler::new(&*path);
/// let mut last = sampler.next();
/// while !sampler.is_finished() {
///     last = sampler.next();
/// }
/// assert_eq!(last.position, end);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan_path_into<N, C, const D: usize, const Q: usize, const Z: usize, const P: usize>(
    curve: C,
    limits: Limits<D>,
    options: StreamOptions,
    stream: &mut Stream<D, Q, Z, C>,
    path: &mut Path<N, D, P>,
) -> Result<(), Error>
where
    N: Number,
    C: StreamCurve<D>,
{
    path.clear();
    let result = stream_pieces(curve, limits, options, stream, path).and_then(|end| {
        let plan = stream.plan_of(&limits);
        seal_streamed(path, &end, &plan)
    });
    if result.is_err() {
        path.clear();
    }
    result
}

/// Streams `curve` as one move into the pieces of `path`, up to its end at rest, and
/// returns the end: the stream's last piece, one tick at rest on the end, is dropped (the
/// path's end sample is that point).
fn stream_pieces<N, C, const D: usize, const Q: usize, const Z: usize, const P: usize>(
    curve: C,
    limits: Limits<D>,
    options: StreamOptions,
    stream: &mut Stream<D, Q, Z, C>,
    path: &mut Path<N, D, P>,
) -> Result<[f64; D], Error>
where
    N: Number,
    C: StreamCurve<D>,
{
    stream.reset(curve.eval(curve.domain().0), limits, options)?;
    stream.push(&Move::curve(curve))?;
    let mut out = PathPieces(&mut path.pieces);
    let (mut finished, mut stalls) = (false, 0);
    loop {
        let mut refused = None;
        if !finished {
            match stream.finish() {
                Ok(()) => finished = true,
                Err(e @ (Error::CapacityExceeded { .. } | Error::ZoneCapacityExceeded { .. })) => {
                    refused = Some(e);
                }
                Err(e) => return Err(e),
            }
        }
        if stream.poll(&mut out)? > 0 {
            stalls = 0;
            continue;
        }
        if finished && stream.is_idle() {
            break;
        }
        if out.room() <= STRETCH_PIECES {
            return Err(Error::CapacityExceeded {
                capacity: P,
                required: out.0.len() + STRETCH_PIECES + 1,
            });
        }
        // Nothing compiled: the window cannot go on (the curve's end refused for a lack of
        // room, or the motion of the next tick not held).
        stalls += 1;
        if stalls > MAX_STALLS {
            return Err(refused.unwrap_or(Error::ZoneCapacityExceeded {
                capacity: Z,
                required: Z + 1,
            }));
        }
    }
    let _rest = out.0.pop();
    stream.position()
}
