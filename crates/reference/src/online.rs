//! Reference for the online solver: the time-optimal jerk-limited motion of one axis from any
//! state to a target state, and the durations it can take.
//!
//! Written independently of `strak-trajectory`'s solver: the seven-phase form with the jerks
//! `(+J, 0, −J, 0, −J, 0, +J)` and its mirror image (Berscheid & Kröger, "Jerk-limited
//! Real-time Trajectory Generation with Arbitrary Target States", RSS 2021, §III), every
//! combination of the limits it reaches, with the phase *durations* as unknowns: the
//! velocity equation is solved in closed form for one of them, and the position residual is
//! scanned over the other on a grid and its roots bisected (sign changes) or its minima
//! refined (touching roots). Every root is integrated phase by phase and kept when every
//! duration is non-negative, the limits hold and the target is reached. A start outside
//! the limits first brakes (the paper's §IV-A: maximal jerk towards the limits, then the
//! acceleration limit held).
//!
//! ```
//! use strak_ref::{OnlineLimits, OnlineState, online_durations};
//! let l = OnlineLimits::symmetric(1.0, 1.0, 1.0);
//! let d = online_durations(&OnlineState::new(0.0, 0.0, 0.0), &OnlineState::new(10.0, 0.0, 0.0), &l);
//! assert!((d.t_min - 12.0).abs() < 1e-9);
//! ```

/// The limits of one axis.
#[derive(Clone, Copy, Debug)]
pub struct OnlineLimits {
    /// Largest velocity.
    pub v_max: f64,
    /// Smallest velocity (< 0).
    pub v_min: f64,
    /// Largest acceleration.
    pub a_max: f64,
    /// Smallest acceleration (< 0).
    pub a_min: f64,
    /// Largest |jerk|.
    pub jerk: f64,
}

impl OnlineLimits {
    /// `|v| ≤ v`, `|a| ≤ a`, `|j| ≤ j`.
    pub fn symmetric(v: f64, a: f64, j: f64) -> Self {
        OnlineLimits {
            v_max: v,
            v_min: -v,
            a_max: a,
            a_min: -a,
            jerk: j,
        }
    }

    fn mirrored(&self) -> Self {
        OnlineLimits {
            v_max: -self.v_min,
            v_min: -self.v_max,
            a_max: -self.a_min,
            a_min: -self.a_max,
            jerk: self.jerk,
        }
    }
}

/// Position, velocity, acceleration.
#[derive(Clone, Copy, Debug)]
pub struct OnlineState {
    /// Position.
    pub p: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration.
    pub a: f64,
}

impl OnlineState {
    /// The state `(p, v, a)`.
    pub fn new(p: f64, v: f64, a: f64) -> Self {
        OnlineState { p, v, a }
    }

    fn after(&self, j: f64, t: f64) -> Self {
        OnlineState {
            p: self.p + self.v * t + self.a * t * t / 2.0 + j * t * t * t / 6.0,
            v: self.v + self.a * t + j * t * t / 2.0,
            a: self.a + j * t,
        }
    }
}

/// The durations one axis can take: the shortest, and the gaps (open intervals it cannot
/// take), and every extremal duration found (sorted).
#[derive(Clone, Debug)]
pub struct OnlineDurations {
    /// The shortest duration (brake included).
    pub t_min: f64,
    /// The gaps.
    pub gaps: Vec<(f64, f64)>,
    /// Every profile's duration found, sorted (the gaps' ends among them).
    pub extremes: Vec<f64>,
}

/// The brake phases `(jerk, duration)` from `(v, a)`: none inside the limits.
pub fn online_brake(v: f64, a: f64, l: &OnlineLimits) -> Vec<(f64, f64)> {
    let j = l.jerk;
    // The velocity once the acceleration is brought to zero at full jerk.
    let settles_up = v + a * a / (2.0 * j);
    let settles_down = v - a * a / (2.0 * j);
    let too_high = (v > l.v_max && settles_down > l.v_min) || (a > 0.0 && settles_up > l.v_max);
    let too_low = (v < l.v_min && settles_up < l.v_max) || (a < 0.0 && settles_down < l.v_min);
    let mirrored = || {
        brake_up(-v, -a, &l.mirrored())
            .into_iter()
            .map(|(jj, t)| (-jj, t))
            .collect()
    };
    if a > l.a_max {
        brake_up(v, a, l)
    } else if a < l.a_min {
        mirrored()
    } else if too_high {
        brake_up(v, a, l)
    } else if too_low {
        mirrored()
    } else {
        Vec::new()
    }
}

/// Brakes a state that is too high (acceleration above its limit, or a velocity that is or
/// will be above its limit).
fn brake_up(v: f64, a: f64, l: &OnlineLimits) -> Vec<(f64, f64)> {
    let j = l.jerk;
    let vel = |t: f64| v + a * t - j * t * t / 2.0;
    if a > l.a_max && vel(a / j) <= l.v_max {
        // Only the acceleration: down to a_max, then held while the velocity is below v_min.
        let t1 = (a - l.a_max) / j;
        let v1 = vel(t1);
        let mut out = vec![(-j, t1)];
        if v1 < l.v_min {
            let hold =
                ((l.v_min - v1) / l.a_max).min((l.v_max - v1) / l.a_max - l.a_max / (2.0 * j));
            out.push((0.0, hold.max(0.0)));
        }
        return out;
    }
    // The velocity: maximal negative jerk until v is back at v_max (or the reversal would
    // reach v_min), the acceleration held at a_min if it gets there first.
    let to_v_max = (a + (a * a + 2.0 * j * (v - l.v_max)).max(0.0).sqrt()) / j;
    let to_v_min = (a + (a * a / 2.0 + j * (v - l.v_min)).max(0.0).sqrt()) / j;
    let first = to_v_max.min(to_v_min);
    let to_a_min = (a - l.a_min) / j;
    if to_a_min < first {
        let v1 = vel(to_a_min);
        let hold = ((l.v_max - v1) / l.a_min).min(l.a_min / (2.0 * j) - (v1 - l.v_min) / l.a_min);
        vec![(-j, to_a_min.max(0.0)), (0.0, hold.max(0.0))]
    } else {
        vec![(-j, first.max(0.0))]
    }
}

/// The problem after the brake, start at position 0.
struct Problem {
    v0: f64,
    a0: f64,
    dp: f64,
    vf: f64,
    af: f64,
    l: OnlineLimits,
    scale_v: f64,
    scale_a: f64,
}

const JERKS: [f64; 7] = [1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0];

impl Problem {
    /// The profile with durations `t` (jerks `J·JERKS`) when it is one: its duration.
    fn check(&self, t: &[f64; 7]) -> Option<f64> {
        let l = &self.l;
        let total: f64 = t.iter().sum();
        let eps_t = 1e-12 * (1.0 + total);
        if t.iter().any(|x| !x.is_finite() || *x < -eps_t) {
            return None;
        }
        let (sv, sa) = (1e-9 * self.scale_v, 1e-9 * self.scale_a);
        let v_ok = |v: f64| v <= l.v_max + sv && v >= l.v_min - sv;
        let mut s = OnlineState::new(0.0, self.v0, self.a0);
        for (i, (&d, &sign)) in t.iter().zip(&JERKS).enumerate() {
            let d = d.max(0.0);
            let j = sign * l.jerk;
            if i >= 2 && j != 0.0 {
                let tz = -s.a / j;
                if tz > 0.0 && tz < d && !v_ok(s.after(j, tz).v) {
                    return None;
                }
            }
            s = s.after(j, d);
            if s.a > l.a_max + sa || s.a < l.a_min - sa || (i >= 2 && !v_ok(s.v)) {
                return None;
            }
        }
        let sp = 1e-8 * (1.0 + self.dp.abs() + self.scale_v * total);
        let ok = (s.p - self.dp).abs() <= sp
            && (s.v - self.vf).abs() <= 1e-8 * (1.0 + self.scale_v + sa * total)
            && (s.a - self.af).abs() <= sa;
        ok.then_some(total)
    }

    /// The end position of the durations `t` minus the target (NaN when `t` is none).
    fn residual(&self, t: &[f64; 7]) -> f64 {
        let mut s = OnlineState::new(0.0, self.v0, self.a0);
        for (&d, &sign) in t.iter().zip(&JERKS) {
            s = s.after(sign * self.l.jerk, d);
        }
        s.p - self.dp
    }

    /// The velocity change of the phases with accelerations `a1` (peak), `a5` (trough):
    /// the sum of `(a'² − a²)/(2j)` over the jerk phases.
    fn all_profiles(&self, out: &mut Vec<f64>) {
        self.cruise(out);
        let (j, l) = (self.l.jerk, &self.l);
        let t1_max = (l.a_max - self.a0) / j;
        let a_span = (l.a_max - l.a_min) / j;
        let t_hold = 4.0 * ((l.v_max - l.v_min) + self.v0.abs() + self.vf.abs())
            / l.a_max.min(-l.a_min)
            + 4.0 * a_span;
        // (a) no hold: scan t1; a5 from the velocity (two branches).
        for branch in [1.0, -1.0] {
            self.scan(0.0, t1_max, out, |t1| {
                let a1 = self.a0 + j * t1;
                let a5sq = (2.0 * a1 * a1 - self.a0 * self.a0 + self.af * self.af
                    - 2.0 * j * (self.vf - self.v0))
                    / 2.0;
                if a5sq < 0.0 {
                    return None;
                }
                let a5 = branch * a5sq.sqrt();
                Some([t1, 0.0, (a1 - a5) / j, 0.0, 0.0, 0.0, (self.af - a5) / j])
            });
        }
        // (b) the peak held at a_max: scan t3; t2 from the velocity.
        let t1 = t1_max;
        self.scan(0.0, a_span, out, |t3| {
            let a5 = l.a_max - j * t3;
            let rest = (l.a_max * l.a_max - self.a0 * self.a0) / (2.0 * j)
                + (l.a_max * l.a_max - a5 * a5) / (2.0 * j)
                + (self.af * self.af - a5 * a5) / (2.0 * j);
            let t2 = (self.vf - self.v0 - rest) / l.a_max;
            Some([t1, t2, t3, 0.0, 0.0, 0.0, (self.af - a5) / j])
        });
        // (c) the trough held at a_min: scan t1; t6 from the velocity.
        self.scan(0.0, t1_max, out, |t1| {
            let a1 = self.a0 + j * t1;
            let a5 = l.a_min;
            let rest = (a1 * a1 - self.a0 * self.a0) / (2.0 * j)
                + (a1 * a1 - a5 * a5) / (2.0 * j)
                + (self.af * self.af - a5 * a5) / (2.0 * j);
            let t6 = (self.vf - self.v0 - rest) / a5;
            Some([t1, 0.0, (a1 - a5) / j, 0.0, 0.0, t6, (self.af - a5) / j])
        });
        // (d) both held: t6 from the velocity is linear in t2, so the residual is a quadratic
        // in t2: interpolated through three values and solved.
        let both = |t2: f64| {
            let (a1, a5) = (l.a_max, l.a_min);
            let rest = (a1 * a1 - self.a0 * self.a0) / (2.0 * j)
                + a1 * t2
                + (a1 * a1 - a5 * a5) / (2.0 * j)
                + (self.af * self.af - a5 * a5) / (2.0 * j);
            let t6 = (self.vf - self.v0 - rest) / a5;
            [t1_max, t2, (a1 - a5) / j, 0.0, 0.0, t6, (self.af - a5) / j]
        };
        let h = 1.0 + t_hold;
        let (r0, r1, r2) = (
            self.residual(&both(0.0)),
            self.residual(&both(h)),
            self.residual(&both(2.0 * h)),
        );
        let qa = (r2 - 2.0 * r1 + r0) / (2.0 * h * h);
        let qb = (r1 - r0) / h - qa * h;
        let disc = qb * qb - 4.0 * qa * r0;
        if disc >= 0.0 && qa != 0.0 {
            for sign in [1.0, -1.0] {
                let root = (-qb + sign * disc.sqrt()) / (2.0 * qa);
                // One Newton step on the residual itself.
                let d = (self.residual(&both(root + 1e-6 * h))
                    - self.residual(&both(root - 1e-6 * h)))
                    / (2e-6 * h);
                let root = if d != 0.0 {
                    root - self.residual(&both(root)) / d
                } else {
                    root
                };
                if let Some(dur) = self.check(&both(root)) {
                    out.push(dur);
                }
            }
        }
    }

    /// The velocity held at `v_max`: the head and tail in closed form, the cruise from the
    /// position.
    fn cruise(&self, out: &mut Vec<f64>) {
        let (j, l) = (self.l.jerk, &self.l);
        let head = self.a0 * self.a0 / 2.0 + j * (l.v_max - self.v0);
        let tail = self.af * self.af / 2.0 + j * (l.v_max - self.vf);
        if head < 0.0 || tail < 0.0 {
            return;
        }
        let mut t = [0.0; 7];
        let a1 = head.sqrt();
        if a1 <= l.a_max {
            t[0] = (a1 - self.a0) / j;
            t[2] = a1 / j;
        } else {
            t[0] = (l.a_max - self.a0) / j;
            t[2] = l.a_max / j;
            let dv =
                (l.a_max * l.a_max - self.a0 * self.a0) / (2.0 * j) + l.a_max * l.a_max / (2.0 * j);
            t[1] = (l.v_max - self.v0 - dv) / l.a_max;
        }
        let a5 = -tail.sqrt();
        if a5 >= l.a_min {
            t[4] = -a5 / j;
            t[6] = (self.af - a5) / j;
        } else {
            t[4] = -l.a_min / j;
            t[6] = (self.af - l.a_min) / j;
            let dv = -l.a_min * l.a_min / (2.0 * j)
                + (self.af * self.af - l.a_min * l.a_min) / (2.0 * j);
            t[5] = (self.vf - l.v_max - dv) / l.a_min;
        }
        let r = self.residual(&t);
        t[3] = -r / l.v_max;
        if let Some(d) = self.check(&t) {
            out.push(d);
        }
    }

    /// Roots of the position residual of `shape(x)` for `x ∈ [lo, hi]`: the residual is
    /// sampled on a grid of 64 cells; the edges of the shape's domain and the extremes of
    /// the residual between samples (refined by a ternary search) are added as points; every
    /// sign change between neighbouring points is bisected, and an extreme that touches
    /// zero is a root itself.
    fn scan(&self, lo: f64, hi: f64, out: &mut Vec<f64>, shape: impl Fn(f64) -> Option<[f64; 7]>) {
        if hi.is_nan() || hi < lo || !hi.is_finite() {
            return;
        }
        let r = |x: f64| {
            shape(x)
                .map(|t| self.residual(&t))
                .filter(|r| r.is_finite())
        };
        const N: usize = 64;
        // A uniform grid, finer in its first cell (phases of a fraction of the first cell's
        // length are common).
        let mut grid: Vec<f64> = (0..=N)
            .map(|i| lo + (hi - lo) * i as f64 / N as f64)
            .collect();
        let cell = (hi - lo) / N as f64;
        grid.splice(1..1, [cell / 64.0, cell / 16.0, cell / 4.0].map(|f| lo + f));
        let mut points: Vec<(f64, f64)> = Vec::new();
        let mut roots = Vec::new();
        let mut prev: Option<(f64, Option<f64>)> = None;
        for &x in &grid {
            let rx = r(x);
            if let Some((px, pr)) = prev {
                // Where the shape stops or starts existing (a square root's domain).
                if pr.is_some() != rx.is_some() {
                    let (mut a, mut b) = (px, x);
                    for _ in 0..100 {
                        let m = 0.5 * (a + b);
                        if r(m).is_some() == pr.is_some() {
                            a = m;
                        } else {
                            b = m;
                        }
                    }
                    let edge = if pr.is_some() { a } else { b };
                    if let Some(re) = r(edge) {
                        points.push((edge, re));
                    }
                }
            }
            if let Some(v) = rx {
                points.push((x, v));
            }
            prev = Some((x, rx));
        }
        // The extremes between samples: where the differences change sign.
        let mut extremes = Vec::new();
        for w in points.windows(3) {
            let (d1, d2) = (w[1].1 - w[0].1, w[2].1 - w[1].1);
            if (d1 > 0.0) != (d2 > 0.0) {
                let sign = if d1 > 0.0 { -1.0 } else { 1.0 }; // a maximum: minimize −r
                let (mut a, mut b) = (w[0].0, w[2].0);
                for _ in 0..100 {
                    let m1 = a + (b - a) / 3.0;
                    let m2 = b - (b - a) / 3.0;
                    match (r(m1), r(m2)) {
                        (Some(f1), Some(f2)) if sign * f1 < sign * f2 => b = m2,
                        (Some(_), Some(_)) => a = m1,
                        _ => break,
                    }
                }
                let x = 0.5 * (a + b);
                if let Some(v) = r(x) {
                    extremes.push((x, v));
                    if v.abs() <= 1e-9 * (1.0 + self.dp.abs()) {
                        roots.push(x);
                    }
                }
            }
        }
        points.extend(extremes);
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in points.windows(2) {
            let ((x0, f0), (x1, f1)) = (w[0], w[1]);
            if f0 == 0.0 {
                roots.push(x0);
            } else if f1 != 0.0 && (f0 < 0.0) != (f1 < 0.0) {
                let (mut a, mut b, mut fa) = (x0, x1, f0);
                for _ in 0..100 {
                    let m = 0.5 * (a + b);
                    match r(m) {
                        Some(fm) if (fm < 0.0) == (fa < 0.0) => {
                            a = m;
                            fa = fm;
                        }
                        Some(_) => b = m,
                        None => break,
                    }
                }
                roots.push(0.5 * (a + b));
            }
        }
        if let Some(&(x, f)) = points.last()
            && f == 0.0
        {
            roots.push(x);
        }
        for x in roots {
            if let Some(d) = shape(x).and_then(|t| self.check(&t)) {
                out.push(d);
            }
        }
    }
}

/// The durations the axis can take from `start` to `target`.
pub fn online_durations(
    start: &OnlineState,
    target: &OnlineState,
    l: &OnlineLimits,
) -> OnlineDurations {
    let brake = online_brake(start.v, start.a, l);
    let mut s = *start;
    let mut brake_time = 0.0;
    for &(j, t) in &brake {
        s = s.after(j, t);
        brake_time += t;
    }
    let scale_v = l.v_max.max(-l.v_min).max(s.v.abs()).max(target.v.abs());
    let scale_a = l.a_max.max(-l.a_min).max(s.a.abs()).max(target.a.abs());
    let up = Problem {
        v0: s.v,
        a0: s.a,
        dp: target.p - s.p,
        vf: target.v,
        af: target.a,
        l: *l,
        scale_v,
        scale_a,
    };
    let down = Problem {
        v0: -s.v,
        a0: -s.a,
        dp: -(target.p - s.p),
        vf: -target.v,
        af: -target.a,
        l: l.mirrored(),
        scale_v,
        scale_a,
    };
    let mut found = Vec::new();
    up.all_profiles(&mut found);
    down.all_profiles(&mut found);
    found.sort_by(f64::total_cmp);
    let mut extremes: Vec<f64> = Vec::new();
    for d in found {
        if extremes.last().is_none_or(|&e| d - e > 1e-9 * (1.0 + e)) {
            extremes.push(d);
        }
    }
    let extremes: Vec<f64> = extremes.into_iter().map(|d| d + brake_time).collect();
    let mut gaps = Vec::new();
    if extremes.len() % 2 == 1 {
        for pair in extremes[1..].chunks(2) {
            gaps.push((pair[0], pair[1]));
        }
    }
    OnlineDurations {
        t_min: extremes.first().copied().unwrap_or(f64::NAN),
        gaps,
        extremes,
    }
}

/// The smallest duration that every axis can take: at least every axis's shortest, outside
/// every axis's gaps.
pub fn online_synchronized(axes: &[OnlineDurations]) -> f64 {
    let mut t = axes.iter().map(|d| d.t_min).fold(0.0, f64::max);
    loop {
        let mut moved = false;
        for d in axes {
            for &(lo, hi) in &d.gaps {
                if t > lo && t < hi {
                    t = hi;
                    moved = true;
                }
            }
        }
        if !moved {
            return t;
        }
    }
}

/// The shortest velocity change from `(v0, a0)` to `(vf, af)` (velocity mode): the
/// acceleration brought into its limits first, then rise–hold–fall or its mirror image,
/// whichever is shorter.
pub fn online_velocity_duration(v0: f64, a0: f64, vf: f64, af: f64, l: &OnlineLimits) -> f64 {
    let j = l.jerk;
    let (mut v, mut a, mut brake) = (v0, a0, 0.0);
    if a > l.a_max || a < l.a_min {
        let target = if a > l.a_max { l.a_max } else { l.a_min };
        let t = (a - target).abs() / j;
        let jj = if a > l.a_max { -j } else { j };
        v += a * t + jj * t * t / 2.0;
        a = target;
        brake = t;
    }
    let one = |v0: f64, a0: f64, vf: f64, af: f64, a_max: f64| -> Option<f64> {
        let mut peak = ((a0 * a0 + af * af) / 2.0 + j * (vf - v0)).max(-1.0);
        if peak < 0.0 {
            return None;
        }
        peak = peak.sqrt();
        let mut hold = 0.0;
        if peak > a_max {
            hold = (vf
                - v0
                - (a_max * a_max - a0 * a0) / (2.0 * j)
                - (a_max * a_max - af * af) / (2.0 * j))
                / a_max;
            peak = a_max;
        }
        let (t1, t3) = ((peak - a0) / j, (peak - af) / j);
        let eps = -1e-12 * (1.0 + a_max / j);
        (t1 >= eps && t3 >= eps && hold >= eps).then(|| t1.max(0.0) + t3.max(0.0) + hold.max(0.0))
    };
    let up = one(v, a, vf, af, l.a_max);
    let down = one(-v, -a, -vf, -af, -l.a_min);
    brake
        + match (up, down) {
            (Some(x), Some(y)) => x.min(y),
            (Some(x), None) | (None, Some(x)) => x,
            (None, None) => f64::NAN,
        }
}
