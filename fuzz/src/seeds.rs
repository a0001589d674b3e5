//! The seed inputs of every target: blobs written by [`Path::to_bytes`], the bundled job
//! and curve files of strak-sim, and fixed pseudo-random bytes for the structured targets.
//! `cargo xtask fuzz` writes them into the corpus folders before a run; the replay test
//! runs them too.

use strak_curves::Bezier;
use strak_trajectory::{Along, CompileOptions, Limits, Number, Path, PathTiming, Q40, compile};

/// One seed: its target, a file name and the bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Seed {
    /// The target's name.
    pub target: &'static str,
    /// A file name for the corpus folder.
    pub name: String,
    /// The input.
    pub bytes: Vec<u8>,
}

/// strak-sim's bundled job and curve files.
const FILES: [(&str, &str); 17] = [
    (
        "job-pick-and-place",
        include_str!("../../firmware-sim/examples/jobs/pick-and-place.toml"),
    ),
    (
        "job-feed-hold",
        include_str!("../../firmware-sim/examples/jobs/feed-hold.toml"),
    ),
    (
        "job-circle-f32",
        include_str!("../../firmware-sim/examples/jobs/circle-f32.toml"),
    ),
    (
        "job-contour-fixed",
        include_str!("../../firmware-sim/examples/jobs/contour-fixed.toml"),
    ),
    (
        "curve-bezier-chain",
        include_str!("../../firmware-sim/examples/bezier-chain.toml"),
    ),
    (
        "curve-bezier",
        include_str!("../../firmware-sim/examples/bezier.toml"),
    ),
    (
        "curve-bspline-closed",
        include_str!("../../firmware-sim/examples/bspline-closed.toml"),
    ),
    (
        "curve-bspline-nonuniform",
        include_str!("../../firmware-sim/examples/bspline-nonuniform.toml"),
    ),
    (
        "curve-bspline",
        include_str!("../../firmware-sim/examples/bspline.toml"),
    ),
    (
        "curve-catmull-rom",
        include_str!("../../firmware-sim/examples/catmull-rom.toml"),
    ),
    (
        "curve-cubic-spline-clamped",
        include_str!("../../firmware-sim/examples/cubic-spline-clamped.toml"),
    ),
    (
        "curve-cubic-spline-periodic",
        include_str!("../../firmware-sim/examples/cubic-spline-periodic.toml"),
    ),
    (
        "curve-cubic-spline",
        include_str!("../../firmware-sim/examples/cubic-spline.toml"),
    ),
    (
        "curve-hermite",
        include_str!("../../firmware-sim/examples/hermite.toml"),
    ),
    (
        "curve-lagrange",
        include_str!("../../firmware-sim/examples/lagrange.toml"),
    ),
    (
        "curve-nurbs-circle",
        include_str!("../../firmware-sim/examples/nurbs-circle.toml"),
    ),
    (
        "curve-parabolic-blend",
        include_str!("../../firmware-sim/examples/parabolic-blend.toml"),
    ),
];

/// Every seed of every target.
pub fn all() -> Vec<Seed> {
    let mut seeds = blobs();
    seeds.extend(FILES.iter().map(|(name, text)| Seed {
        target: "job",
        name: format!("{name}.toml"),
        bytes: text.as_bytes().to_vec(),
    }));
    for target in ["curves", "pipeline"] {
        seeds.extend(random(target, 16));
    }
    seeds
}

/// `count` inputs of 32 to 287 bytes from a fixed xorshift sequence.
fn random(target: &'static str, count: usize) -> Vec<Seed> {
    let mut x = 0x9E37_79B9_7F4A_7C15_u64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    (0..count)
        .map(|i| {
            let len = 32 + (next() % 256) as usize;
            let bytes = (0..len).map(|_| next().to_le_bytes()[0]).collect();
            Seed {
                target,
                name: format!("random-{i:02}"),
                bytes,
            }
        })
        .collect()
}

/// A short S-curve move along a straight line in `A` axes (a quadratic Bézier curve with
/// uneven parametric speed), compiled at 1 kHz, serialized.
fn blob<N: Number, const A: usize>() -> Option<Vec<u8>> {
    let p = |s: f64| -> [f64; A] { core::array::from_fn(|i| s * (3.0 - i as f64)) };
    let curve = Bezier::new([p(0.0), p(0.2), p(1.0)]).ok()?;
    let limits = Limits::<A>::new(40.0, 400.0, 20_000.0).ok()?;
    let timing = PathTiming::<_, 64, 8>::scurve(&curve, &limits).ok()?;
    let options = CompileOptions::new().with_path_limits(&limits);
    let path: Path<N, A, 16> = compile(&Along::new(&curve, &timing), 1_000.0, &options).ok()?;
    let mut bytes = vec![0_u8; path.blob_len()];
    path.to_bytes(&mut bytes).ok()?;
    Some(bytes)
}

fn blobs() -> Vec<Seed> {
    macro_rules! seed {
        ($n:ty, $a:literal) => {
            blob::<$n, $a>().map(|bytes| Seed {
                target: "blob",
                name: format!("{}-{}axes.blob", <$n as Number>::NAME, $a),
                bytes,
            })
        };
    }
    [
        seed!(f32, 1),
        seed!(f32, 3),
        seed!(f64, 2),
        seed!(f64, 6),
        seed!(Q40, 1),
        seed!(Q40, 3),
        seed!(Q40, 4),
    ]
    .into_iter()
    .flatten()
    .collect()
}
