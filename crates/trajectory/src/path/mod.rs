//! The compiled path: polynomial pieces in control ticks stored as forward-difference states
//! ([`AxisState`], [`Piece`]), the rest of its description ([`PathHeader`]), the owned path
//! in RAM ([`Path`]), a validated blob read in place ([`PathBlob`]), and the capacity-free
//! view that the sampler plays ([`PathView`]).

mod blob;
mod header;
mod owned;
mod sample;
mod state;
pub(crate) mod view;

pub use blob::{AlignedBlob, BLOB_MAGIC, BLOB_VERSION, PathBlob, crc32};
pub use header::{END_AGREEMENT_SLACK, PathHeader};
pub(crate) use header::{FeedRampLimits, MIN_ALPHA, PathEnd, PathMeta, RampBasis, feed_ramp_f64};
pub use owned::Path;
pub use sample::Sample;
pub(crate) use state::Newton;
pub use state::{AxisState, Piece};
pub use view::PathView;
