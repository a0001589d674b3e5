//! Curves and closed forms shared by the tests of the profile modules.

extern crate std;

use strak_curves::{Bezier, ParamCurve, ParamCurveDeriv};

/// A quintic shaped like a corner blend, turning by a right angle with its curvature
/// rising from zero and falling back.
pub(crate) fn blend_like_quintic() -> Bezier<[f64; 2], 6> {
    let points = [
        [0.0, 0.0],
        [0.4, 0.0],
        [0.75, 0.02],
        [1.0, 0.25],
        [1.0, 0.6],
        [1.0, 1.0],
    ];
    Bezier::new(points).unwrap_or_else(|e| panic!("{e}"))
}

/// Time-optimal rest-to-rest double S duration for a distance `l` (Biagiotti & Melchiorri,
/// §3.4, eqs. 3.25–3.27 with `v0 = v1 = 0`), written independently of the planner.
pub(super) fn textbook_scurve_duration(l: f64, v: f64, a: f64, j: f64) -> f64 {
    // Is v_max reached? (3.19)
    let ta = if v * j < a * a {
        2.0 * (v / j).sqrt()
    } else {
        a / j + v / a
    };
    let tv = l / v - ta;
    if tv > 0.0 {
        return 2.0 * ta + tv;
    }
    // v_max is not reached; assume a_max is (3.26a)
    let tj = a / j;
    let delta = a.powi(4) / (j * j) + 4.0 * a * l;
    let ta = (a * a / j + delta.sqrt()) / (2.0 * a);
    if ta >= 2.0 * tj {
        return 2.0 * ta;
    }
    // a_max is not reached either (3.26b): T_j = (L / (2 j))^(1/3), T = 4 T_j
    4.0 * (l / (2.0 * j)).cbrt()
}

/// A straight line of length `l1` along +x ending at the origin (u ∈ [0, 1]), a quarter
/// circle of radius `r` turning left (u ∈ [1, 2]), and a line of length `l2` along +y
/// (u ∈ [2, 3]): tangent continuous (G¹), with the parametric speed and the curvature
/// jumping at the joins.
#[derive(Clone, Copy, Debug)]
pub(super) struct LineArcLine {
    l1: f64,
    r: f64,
    l2: f64,
}

impl LineArcLine {
    pub(super) fn new(l1: f64, r: f64, l2: f64) -> Self {
        LineArcLine { l1, r, l2 }
    }

    fn piece(&self, u: f64) -> usize {
        if u < 1.0 {
            0
        } else if u < 2.0 {
            1
        } else {
            2
        }
    }
}

impl ParamCurve for LineArcLine {
    type Point = [f64; 2];

    fn domain(&self) -> (f64, f64) {
        (0.0, 3.0)
    }

    fn eval(&self, u: f64) -> [f64; 2] {
        self.deriv(u, 0)
    }

    fn piece_count(&self) -> usize {
        3
    }

    fn piece_domain(&self, i: usize) -> (f64, f64) {
        let i = i.min(2) as f64;
        (i, i + 1.0)
    }
}

impl ParamCurveDeriv for LineArcLine {
    fn deriv(&self, u: f64, k: usize) -> [f64; 2] {
        let u = u.clamp(0.0, 3.0);
        let w = core::f64::consts::FRAC_PI_2;
        match (self.piece(u), k) {
            (0, 0) => [-self.l1 + self.l1 * u, 0.0],
            (0, 1) => [self.l1, 0.0],
            (1, 0) => {
                let th = (u - 1.0) * w;
                [self.r * th.sin(), self.r * (1.0 - th.cos())]
            }
            (1, k) => {
                let th = (u - 1.0) * w + k as f64 * w;
                let f = self.r * w.powi(k as i32);
                [f * th.sin(), -f * th.cos()]
            }
            (_, 0) => [self.r, self.r + self.l2 * (u - 2.0)],
            (_, 1) => [0.0, self.l2],
            _ => [0.0, 0.0],
        }
    }
}
