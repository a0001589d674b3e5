//! Planning a rest-to-rest motion along a curve with a speed limit varying along the path:
//! zones, the forward/backward pass over the zone boundaries, and a profile per zone (the
//! algorithm is described on [`PlanOptions`]).

use strak_curves::{ArcLengthTable, ParamCurveDeriv};

use super::limits::Limits;
use super::motion::{MotionProfile, ProfileZone};
use super::options::PlanOptions;
use super::scurve::{fill_zone, reach};
use super::speed_limit::{TableArcs, zones_into};
use super::transitions::carry_acceleration;
use crate::error::Error;

/// The forward/backward pass over the zone boundaries: sets `v_start`, `v_end` of every
/// zone so that each zone can go from one to the other within its length and limits, and
/// no zone ends faster than its exit cap (0 at corners and cusps). Starts and ends at rest.
fn boundary_speeds(zones: &mut [ProfileZone]) {
    let mut v = 0.0;
    for i in 0..zones.len() {
        let next_limit = zones.get(i + 1).map_or(0.0, |z| z.v_limit);
        if let Some(z) = zones.get_mut(i) {
            z.v_start = v;
            let cap = z.v_limit.min(next_limit).min(z.exit_cap);
            z.v_end = reach(v, z.end - z.start, cap, z.a_limit, z.j_limit);
            v = z.v_end;
        }
    }
    let mut v = 0.0;
    for z in zones.iter_mut().rev() {
        z.v_end = z.v_end.min(v);
        z.v_start = reach(z.v_end, z.end - z.start, z.v_start, z.a_limit, z.j_limit);
        v = z.v_start;
    }
}

/// The motion through `zones` (whose extents, limits and caps are set), in place: the
/// boundary speeds, a profile per zone, and the transitions that carry the acceleration
/// across boundaries where that is faster.
fn fill_zones(zones: &mut [ProfileZone]) {
    double_s_zones(zones);
    carry_acceleration(zones);
}

/// The boundary speeds and the double S of each zone, from and to zero acceleration.
fn double_s_zones(zones: &mut [ProfileZone]) {
    boundary_speeds(zones);
    let (mut t, mut s) = (0.0, 0.0);
    for z in zones.iter_mut() {
        z.t_start = t;
        fill_zone(z, s);
        t = z.t_end();
        s = z.end_state().s;
    }
}

/// Plans the motion along `curve` (whose arc-length table is `table`) under `limits` less
/// the feed reserve into `motion`, in place: zones of the speed limit, boundary speeds, and
/// a profile per zone. `options` must be valid and the axis count checked.
///
/// # Errors
/// As [`zones_into`]; [`Error::TooLong`] when the motion takes more ticks at the plan's rate
/// than a `u32` counts.
pub(super) fn plan_motion_into<C, const A: usize, const N: usize, const Z: usize>(
    curve: &C,
    table: &ArcLengthTable<f64, N>,
    limits: &Limits<A>,
    options: &PlanOptions,
    motion: &mut MotionProfile<Z>,
) -> Result<(), Error>
where
    C: ParamCurveDeriv,
{
    let planned = limits.without_reserve(options.feed_share());
    motion.zones.clear();
    let arcs = TableArcs { curve, table };
    zones_into(curve, &arcs, &planned, options, &mut motion.zones)?;
    fill_zones(&mut motion.zones);
    motion.seal(table.length())?;
    if motion.duration() * options.rate() > f64::from(u32::MAX) {
        return Err(Error::TooLong);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec as StdVec;

    use super::*;
    use crate::plan::motion::Phase;
    use crate::plan::options::{MAX_SAMPLES, ProfileShape};
    use crate::plan::scurve::change_distance;
    use crate::plan::testcurves::{LineArcLine, textbook_scurve_duration};
    use crate::plan::to_param;
    use crate::{PathTiming, Timing};
    use strak_curves::{Bezier, Nurbs, ParamCurve, Point, Scalar};

    /// The machine limits whose planned part (less the default feed reserve) is `planned`.
    fn full<const A: usize>(planned: &Limits<A>) -> Limits<A> {
        let k = 1.0 - PlanOptions::DEFAULT_FEED_SHARE;
        Limits::new(
            planned.velocity(),
            planned.acceleration() / k,
            planned.jerk() / k,
        )
        .and_then(|m| m.with_axis_velocity(planned.axis_velocity()))
        .and_then(|m| m.with_axis_acceleration(planned.axis_acceleration().map(|a| a / k)))
        .unwrap()
    }

    /// The per-axis and path limits at `u`, computed directly: (v_lim, T, κN).
    fn limit_at<C: ParamCurveDeriv>(
        c: &C,
        u: f64,
        limits: &Limits<2>,
        share: f64,
    ) -> (f64, [f64; 2], [f64; 2]) {
        let d1 = c.deriv(to_param(c, u), 1).to_f64_array();
        let d2 = c.deriv(to_param(c, u), 2).to_f64_array();
        let sp = (d1[0] * d1[0] + d1[1] * d1[1]).sqrt();
        let t = [d1[0] / sp, d1[1] / sp];
        // κN = (c' × c'') / |c'|³ rotated: for 2-D, κ = |x'y'' − y'x''| / |c'|³
        let cross = d1[0] * d2[1] - d1[1] * d2[0];
        let kappa = cross / (sp * sp * sp);
        let n = [-t[1] * kappa, t[0] * kappa];
        let mut v = limits.velocity();
        if kappa != 0.0 {
            v = v.min((share * limits.acceleration() / kappa.abs()).sqrt());
        }
        for i in 0..2 {
            v = v.min(limits.axis_velocity()[i] / t[i].abs());
            v = v.min((share * limits.axis_acceleration()[i] / n[i].abs()).sqrt());
        }
        (v, t, n)
    }

    struct Measured {
        v_ratio: f64,
        a_ratio: f64,
        j_ratio: f64,
        axis_v_ratio: f64,
        axis_a_ratio: f64,
        centripetal_ratio: f64,
        /// `|ẍ|/a_max` of the composed motion in space.
        space_a_ratio: f64,
        /// `|x⃛|/j_max` of the composed motion in space.
        space_j_ratio: f64,
    }

    /// Samples the planned motion: continuity of s, v, a; limits; the composed motion.
    fn check<C: ParamCurveDeriv, const N: usize, const Z: usize>(
        c: &C,
        timing: &PathTiming<'_, C, N, Z>,
        limits: &Limits<2>,
        share: f64,
        jerk: f64,
        steps: usize,
    ) -> Measured {
        let m = timing.motion();
        let d = m.duration();
        let mut out = Measured {
            v_ratio: 0.0,
            a_ratio: 0.0,
            j_ratio: 0.0,
            axis_v_ratio: 0.0,
            axis_a_ratio: 0.0,
            centripetal_ratio: 0.0,
            space_a_ratio: 0.0,
            space_j_ratio: 0.0,
        };
        let dt = d / steps as f64;
        let mut prev = m.state(0.0);
        assert_eq!((prev.s, prev.v), (0.0, 0.0));
        let aj = jerk;
        let xdot = |t: f64| -> [f64; 2] {
            let (u, du) = timing.param(t);
            let d1 = c.deriv(to_param(c, u), 1).to_f64_array();
            [d1[0] * du, d1[1] * du]
        };
        for k in 1..=steps {
            let t = dt * k as f64;
            let st = m.state(t);
            // continuity: |Δs| ≤ v dt + ..., |Δv| ≤ a_max dt, |Δa| ≤ j_max dt
            assert!(
                (st.s - prev.s) >= -1e-12 && (st.s - prev.s) <= limits.velocity() * dt * 1.0001
            );
            assert!((st.v - prev.v).abs() <= limits.acceleration() * dt * 1.0001);
            assert!((st.a - prev.a).abs() <= aj * dt * 1.0001 + 1e-9);
            prev = st;
            let (u, _) = timing.param(t);
            let (vlim, tan, kn) = limit_at(c, u, limits, share);
            out.v_ratio = out.v_ratio.max(st.v / vlim);
            out.a_ratio = out.a_ratio.max(st.a.abs() / limits.acceleration());
            out.j_ratio = out.j_ratio.max(st.j.abs() / limits.jerk());
            let kappa = (kn[0] * kn[0] + kn[1] * kn[1]).sqrt();
            out.centripetal_ratio = out
                .centripetal_ratio
                .max(st.v * st.v * kappa / limits.acceleration());
            // per-axis velocity of the composed motion
            let xd = xdot(t);
            for i in 0..2 {
                out.axis_v_ratio = out
                    .axis_v_ratio
                    .max(xd[i].abs() / limits.axis_velocity()[i]);
                assert!((xd[i].abs() - tan[i].abs() * st.v).abs() <= 1e-6 * (1.0 + st.v));
            }
            // acceleration (per axis and in space) and jerk in space of the composed motion,
            // by central differences of ẋ
            if t > 2.0 * dt && t < d - 2.0 * dt {
                let h = 1e-2 * dt;
                let (xp, xm) = (xdot(t + h), xdot(t - h));
                let (mut a2, mut j2) = (0.0, 0.0);
                for i in 0..2 {
                    let xdd = (xp[i] - xm[i]) / (2.0 * h);
                    let xddd = (xp[i] - 2.0 * xd[i] + xm[i]) / (h * h);
                    a2 += xdd * xdd;
                    j2 += xddd * xddd;
                    out.axis_a_ratio = out
                        .axis_a_ratio
                        .max(xdd.abs() / limits.axis_acceleration()[i]);
                }
                out.space_a_ratio = out.space_a_ratio.max(a2.sqrt() / limits.acceleration());
                out.space_j_ratio = out.space_j_ratio.max(j2.sqrt() / limits.jerk());
            }
        }
        let end = m.state(d);
        assert_eq!((end.s, end.v, end.a), (timing.length(), 0.0, 0.0));
        assert_eq!(timing.param(d), (c.domain().1.to_f64(), 0.0));
        out
    }

    #[test]
    fn straight_line_matches_closed_form() {
        // uneven parametric speed along a straight line of length 100
        // (all points on the line y = 4x/3, unevenly spaced)
        let c = Bezier::new([[0.0, 0.0], [3.0, 4.0], [12.0, 16.0], [60.0, 80.0]]).unwrap();
        for &(v, a, j) in &[
            (10.0, 20.0, 100.0),  // v_max and a_max reached
            (2.0, 20.0, 100.0),   // v_max reached, a_max not
            (60.0, 20.0, 1000.0), // a_max reached, v_max not
            (60.0, 500.0, 100.0), // neither
        ] {
            let limits = Limits::<2>::new(v, a, j).unwrap();
            let timing = PathTiming::<_, 128, 8>::scurve(&c, &full(&limits)).unwrap();
            assert_eq!(timing.motion().zones().len(), 1);
            let l = timing.length();
            assert!((l - 100.0).abs() < 1e-8);
            let exact = textbook_scurve_duration(100.0, v, a, j);
            let rel = (timing.duration() - exact).abs() / exact;
            std::println!(
                "line v={v} a={a} j={j}: T = {} closed form {exact} rel {rel:e}",
                timing.duration()
            );
            assert!(rel < 1e-3);
            assert!(rel < 1e-9);
            let meas = check(&c, &timing, &limits, 0.5, limits.jerk(), 2000);
            assert!(meas.v_ratio <= 1.0 + 1e-9 && meas.a_ratio <= 1.0 + 1e-9);
            assert!(meas.j_ratio <= 1.0 + 1e-12);
            std::println!(
                "  in space: |ẍ|/a_max {} |x⃛|/j_max {}",
                meas.space_a_ratio,
                meas.space_j_ratio
            );
            // (second differences of ẋ through the arc-length table: within 10⁻³)
            assert!(meas.space_a_ratio <= 1.0 + 1e-6 && meas.space_j_ratio <= 1.0 + 1e-3);
        }
    }

    #[test]
    fn tight_curve_slows_only_there() {
        let c = LineArcLine::new(100.0, 2.0, 100.0);
        let limits = Limits::<2>::new(50.0, 100.0, 2000.0).unwrap();
        let timing = PathTiming::<_, 256, 64>::scurve(&c, &full(&limits)).unwrap();
        let m = timing.motion();
        // the arc limits the speed to √(q a r) = √(0.5·100·2) = 10 (its turning jerk
        // v³κ² = v³/4 to q·j_max at ∛4000 ≈ 15.9)
        let v_arc = (0.5_f64 * 100.0 * 2.0).sqrt();
        let slowest = m
            .zones()
            .iter()
            .map(|z| z.v_limit())
            .fold(f64::INFINITY, f64::min);
        assert!((slowest - v_arc).abs() < 1e-6 * v_arc, "slowest {slowest}");
        assert!(
            m.zones().len() >= 3 && m.zones().len() <= 5,
            "{} zones",
            m.zones().len()
        );
        // a plan with the global minimum limit everywhere
        let global = MotionProfile::<1>::scurve(timing.length(), v_arc, 100.0, 2000.0).unwrap();
        std::println!(
            "tight curve: T = {} (global-minimum plan {}), {} zones",
            m.duration(),
            global.duration(),
            m.zones().len()
        );
        assert!(m.duration() < 0.6 * global.duration());
        // fast on the straights, slow in the arc
        let mut v_on_arc: f64 = 0.0;
        let mut v_on_line: f64 = 0.0;
        for k in 0..=4000 {
            let t = m.duration() * k as f64 / 4000.0;
            let st = m.state(t);
            let (u, _) = timing.param(t);
            if (1.0..=2.0).contains(&u) {
                v_on_arc = v_on_arc.max(st.v);
            } else {
                v_on_line = v_on_line.max(st.v);
            }
        }
        assert!(v_on_arc <= v_arc * (1.0 + 1e-9));
        assert!((v_on_line - 50.0).abs() < 1e-9);
        let meas = check(&c, &timing, &limits, 0.5, limits.jerk(), 20_000);
        std::println!(
            "tight curve ratios: v/v_lim {} |s̈|/a_max {} |s⃛|/j_max {} v²κ/a_max {} |ẍ|/a_max {}",
            meas.v_ratio,
            meas.a_ratio,
            meas.j_ratio,
            meas.centripetal_ratio,
            meas.space_a_ratio,
        );
        assert!(meas.v_ratio <= 1.0 + 1e-6);
        assert!(meas.a_ratio <= 1.0 + 1e-9);
        assert!(meas.j_ratio <= 1.0 + 1e-12);
        assert!(meas.centripetal_ratio <= 0.5 + 1e-6);
        // the acceleration in space holds; its jerk does not at the two joins, where the
        // curvature jumps from 0 to 1/2 (a G¹ path: see `PathTiming::plan`)
        assert!(meas.space_a_ratio <= 1.0 + 1e-6);
        // boundaries: continuous v and a = 0
        for w in m.zones().windows(2) {
            assert_eq!(w[0].v_end(), w[1].v_start());
            assert!(w[0].v_end() <= w[0].v_limit().min(w[1].v_limit()));
            assert!(
                change_distance(w[0].v_start(), w[0].v_end(), w[0].a_limit(), 2000.0)
                    <= (w[0].end() - w[0].start()) * (1.0 + 1e-12)
            );
        }
    }

    #[test]
    fn circle_centripetal_limit() {
        // radius 10, a_max 1000, q = 0.5: v ≤ √(q a r) = √5000 ≈ 70.7 < v_max 500; the
        // turning jerk v³κ² allows ∛(q j r²) = ∛10⁶ = 100
        let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).unwrap();
        let limits = Limits::<2>::new(500.0, 1000.0, 20_000.0).unwrap();
        let timing = PathTiming::<_, 256, 4>::scurve(&c, &full(&limits)).unwrap();
        let m = timing.motion();
        assert_eq!(m.zones().len(), 1);
        let z = m.zones()[0];
        let v = 5000.0_f64.sqrt();
        assert!((z.v_limit() - v).abs() < 1e-9);
        // tangential budget: what v²κ = 500 leaves of a_max, and the fastest split of what
        // v³κ² leaves of j_max between s⃛ and the term 3vκ·s̈
        let (centripetal, turn_jerk) = (500.0, v * v * v * 0.01);
        let a = (1e6_f64 - centripetal * centripetal).sqrt();
        let (rest, turning) = (20_000.0 - turn_jerk, 3.0 * v * 0.1);
        let a = a.min(v.sqrt() * rest / (rest.sqrt() + turning * v.sqrt()));
        assert!((z.a_limit() - a).abs() < 1e-9 * a);
        let j = 20_000.0 - turn_jerk - 3.0 * v * 0.1 * a;
        assert!((z.j_limit() - j).abs() < 1e-9 * j);
        let l = 2.0 * core::f64::consts::PI * 10.0;
        assert!((timing.length() - l).abs() < 1e-8);
        let exact = textbook_scurve_duration(l, v, a, j);
        assert!((m.duration() - exact).abs() < 1e-9 * exact);
        let meas = check(&c, &timing, &limits, 0.5, limits.jerk(), 10_000);
        std::println!(
            "circle: v²κ/a_max max {} |ẍ|/a_max {} |x⃛|/j_max {}",
            meas.centripetal_ratio,
            meas.space_a_ratio,
            meas.space_j_ratio
        );
        assert!(meas.centripetal_ratio <= 0.5 + 1e-9);
        assert!(meas.centripetal_ratio > 0.499);
        assert!(meas.space_a_ratio <= 1.0 + 1e-6);
        assert!(meas.space_j_ratio <= 1.0 + 1e-3);
    }

    #[test]
    fn bezier_arc_in_f32_and_f64() {
        use strak_curves::glam::{DVec2, Vec2};
        // the seed's cubic quarter circle of radius 1:
        // κ ≈ 1, a_max = 4, q = 0.5 → v ≤ ≈ √2 < v_max = 3 (turning jerk: ∛25 ≈ 2.9)
        let c64 = Bezier::<DVec2, 4>::quarter_circle(strak_curves::QUARTER_CIRCLE_KAPPA).unwrap();
        let c32 =
            Bezier::<Vec2, 4>::quarter_circle(strak_curves::QUARTER_CIRCLE_KAPPA as f32).unwrap();
        let limits = Limits::<2>::new(3.0, 4.0, 50.0).unwrap();
        let t64 = PathTiming::<_, 128, 16>::scurve(&c64, &full(&limits)).unwrap();
        let t32 = PathTiming::<_, 128, 16>::scurve(&c32, &full(&limits)).unwrap();
        let slowest = t64
            .motion()
            .zones()
            .iter()
            .map(|z| z.v_limit())
            .fold(f64::INFINITY, f64::min);
        // the cubic's curvature varies by about ±1 % around 1
        assert!((slowest - 2.0_f64.sqrt()).abs() < 2e-2, "{slowest}");
        let rel = (t64.duration() - t32.duration()).abs() / t64.duration();
        std::println!(
            "Bézier arc: T64 = {} T32 = {} rel {rel:e}, zones {}",
            t64.duration(),
            t32.duration(),
            t64.motion().zones().len()
        );
        assert!(rel < 1e-5);
        let meas = check(&c64, &t64, &limits, 0.5, limits.jerk(), 5000);
        std::println!(
            "Bézier arc: v²κ/a_max {} v/v_lim {} |ẍ|/a_max {} |x⃛|/j_max {}",
            meas.centripetal_ratio,
            meas.v_ratio,
            meas.space_a_ratio,
            meas.space_j_ratio
        );
        assert!(meas.centripetal_ratio <= 0.5 + 1e-6 && meas.centripetal_ratio > 0.49);
        assert!(meas.v_ratio <= 1.0 + 1e-6);
        assert!(meas.space_a_ratio <= 1.0 + 1e-6);
        assert!(meas.space_j_ratio <= 1.0 + 1e-3);
    }

    #[test]
    fn per_axis_limits_on_a_circle() {
        let c = Nurbs::<[f64; 2], 9, 12>::circle([0.0, 0.0], 10.0).unwrap();
        let limits = Limits::<2>::new(500.0, 1000.0, 20_000.0)
            .unwrap()
            .with_axis_velocity([40.0, f64::INFINITY])
            .unwrap()
            .with_axis_acceleration([f64::INFINITY, 300.0])
            .unwrap();
        let share = 0.5;
        let timing = PathTiming::<_, 256, 128>::scurve(&c, &full(&limits)).unwrap();
        let meas = check(&c, &timing, &limits, share, limits.jerk(), 20_000);
        std::println!(
            "circle per axis: {} zones, T = {}, v/v_lim {} |ẋ_i|/v_i {} |ẍ_i|/a_i {}",
            timing.motion().zones().len(),
            timing.duration(),
            meas.v_ratio,
            meas.axis_v_ratio,
            meas.axis_a_ratio
        );
        assert!(meas.axis_v_ratio <= 1.0 + 1e-4);
        assert!(meas.axis_a_ratio <= 1.0 + 1e-3);
        assert!(meas.v_ratio <= 1.0 + 1e-3);
        std::println!(
            "circle per axis: |ẍ|/a_max {} |x⃛|/j_max {}",
            meas.space_a_ratio,
            meas.space_j_ratio
        );
        assert!(meas.space_a_ratio <= 1.0 + 1e-3);
        assert!(meas.space_j_ratio <= 1.0 + 1e-3);
        // the limits bind: the x axis runs at its speed limit somewhere
        assert!(meas.axis_v_ratio > 0.9);
        // and it is slower than the path limits alone
        let free = PathTiming::<_, 256, 128>::scurve(
            &c,
            &full(&Limits::<2>::new(500.0, 1000.0, 20_000.0).unwrap()),
        )
        .unwrap();
        assert!(timing.duration() > free.duration());
    }

    #[test]
    fn per_axis_velocity_on_a_line() {
        // direction (0.6, 0.8): the y axis limit 4 allows 4/0.8 = 5
        let c = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).unwrap();
        let limits = Limits::<2>::new(10.0, 20.0, 200.0)
            .unwrap()
            .with_axis_velocity([100.0, 4.0])
            .unwrap();
        let timing = PathTiming::<_, 16, 4>::scurve(&c, &full(&limits)).unwrap();
        let exact = textbook_scurve_duration(50.0, 5.0, 20.0, 200.0);
        assert!((timing.duration() - exact).abs() < 1e-9 * exact);
        let meas = check(&c, &timing, &limits, 0.5, limits.jerk(), 2000);
        assert!(meas.axis_v_ratio <= 1.0 + 1e-9 && meas.axis_v_ratio > 1.0 - 1e-9);
        // per-axis acceleration on a line: |ẍ_y| = |s̈|·0.8 ≤ 8 → a ≤ 10
        let limits = Limits::<2>::new(10.0, 20.0, 200.0)
            .unwrap()
            .with_axis_acceleration([100.0, 8.0])
            .unwrap();
        let timing = PathTiming::<_, 16, 4>::scurve(&c, &full(&limits)).unwrap();
        assert!((timing.motion().zones()[0].a_limit() - 10.0).abs() < 1e-12);
        let exact = textbook_scurve_duration(50.0, 10.0, 10.0, 200.0);
        assert!((timing.duration() - exact).abs() < 1e-9 * exact);
        let meas = check(&c, &timing, &limits, 0.5, limits.jerk(), 2000);
        assert!(meas.axis_a_ratio <= 1.0 + 1e-6 && meas.axis_a_ratio > 0.99);
    }

    #[test]
    fn trapezoid_shape_with_varying_limits() {
        let c = LineArcLine::new(100.0, 2.0, 100.0);
        let limits = Limits::<2>::new(50.0, 100.0, 2000.0).unwrap();
        let options = PlanOptions::new().with_shape(ProfileShape::Trapezoid);
        let trap = PathTiming::<_, 256, 64>::plan(&c, &full(&limits), &options).unwrap();
        let s = PathTiming::<_, 256, 64>::scurve(&c, &full(&limits)).unwrap();
        // the trapezoid ignores the jerk limit: faster
        assert!(trap.duration() < s.duration());
        for p in trap.motion().phases() {
            assert_eq!(p.j, 0.0);
            assert!(p.a0.abs() <= 100.0);
        }
        let meas = check(&c, &trap, &limits, 0.5, f64::INFINITY, 5000);
        assert!(meas.v_ratio <= 1.0 + 1e-6);
    }

    /// Five zones: the lines, the arc, and the sampling intervals that reach the joins from
    /// the lines' side (the arc's curvature in their last sample), which end where the
    /// curvature step caps the speed.
    #[test]
    fn capacity_exceeded_for_zones() {
        let c = LineArcLine::new(100.0, 2.0, 100.0);
        let limits = Limits::<2>::new(50.0, 100.0, 2000.0).unwrap();
        let r = PathTiming::<_, 64, 2>::scurve(&c, &full(&limits));
        assert!(matches!(
            r,
            Err(Error::ZoneCapacityExceeded {
                capacity: 2,
                required: 5
            })
        ));
        // a continuously varying limit with tolerance 0 needs many zones
        let b = Bezier::new([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]).unwrap();
        let o = PlanOptions::new()
            .with_zone_tolerance(0.0)
            .with_samples(100);
        let r =
            PathTiming::<_, 64, 8>::plan(&b, &Limits::<2>::new(100.0, 10.0, 100.0).unwrap(), &o);
        assert!(matches!(
            r,
            Err(Error::ZoneCapacityExceeded { capacity: 8, required }) if required > 8
        ));
    }

    #[test]
    fn option_and_limit_errors() {
        let c = Bezier::new([[0.0, 0.0], [3.0, 4.0]]).unwrap();
        let l = Limits::<2>::new(1.0, 1.0, 1.0).unwrap();
        for o in [
            PlanOptions::new().with_samples(0),
            PlanOptions::new().with_samples(MAX_SAMPLES + 1),
            PlanOptions::new().with_zone_tolerance(-0.1),
            PlanOptions::new().with_zone_tolerance(f64::NAN),
            PlanOptions::new().with_centripetal_share(0.0),
            PlanOptions::new().with_centripetal_share(1.0),
            PlanOptions::new().with_corner_angle(0.0),
            PlanOptions::new().with_corner_angle(f64::NAN),
            PlanOptions::new().with_corner_angle(f64::INFINITY),
        ] {
            assert!(matches!(
                PathTiming::<_, 8, 4>::plan(&c, &l, &o),
                Err(Error::InvalidLimit)
            ));
        }
        // InvalidLimit comes from Limits itself
        assert_eq!(Limits::<2>::new(1.0, 0.0, 1.0), Err(Error::InvalidLimit));
        let still = Bezier::new([[1.0, 1.0], [1.0, 1.0]]).unwrap();
        assert!(matches!(
            PathTiming::<_, 8, 4>::scurve(&still, &l),
            Err(Error::EmptyPath)
        ));
        assert!(matches!(
            PathTiming::<_, 8, 4>::scurve(&c, &Limits::<1>::new(1.0, 1.0, 1.0).unwrap()),
            Err(Error::AxisMismatch { curve: 2, path: 1 })
        ));
        assert!(matches!(
            PathTiming::<_, 8, 0>::scurve(&c, &l),
            Err(Error::ZoneCapacityExceeded {
                capacity: 0,
                required: 1
            })
        ));
    }

    #[test]
    fn deterministic_plan() {
        let c = LineArcLine::new(100.0, 2.0, 100.0);
        let limits = Limits::<2>::new(50.0, 100.0, 2000.0).unwrap();
        let a = PathTiming::<_, 128, 16>::scurve(&c, &full(&limits)).unwrap();
        let b = PathTiming::<_, 128, 16>::scurve(&c, &full(&limits)).unwrap();
        let bits = |t: &PathTiming<'_, LineArcLine, 128, 16>| -> StdVec<u64> {
            t.motion()
                .phases()
                .flat_map(|p| [p.t0, p.duration, p.s0, p.v0, p.a0, p.j])
                .map(f64::to_bits)
                .collect()
        };
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a.param(1.234).0.to_bits(), b.param(1.234).0.to_bits());
    }

    /// A polyline (0,0) → (50,0) → 50 more at the turn `radians` (a degree-1 B-spline).
    fn polyline(radians: f64) -> strak_curves::BSpline<[f64; 2], 4, 8> {
        let pts = [
            [0.0, 0.0],
            [50.0, 0.0],
            [50.0 + 50.0 * radians.cos(), 50.0 * radians.sin()],
        ];
        strak_curves::BSpline::clamped_uniform(1, &pts, 0.0, 1.0).unwrap()
    }

    #[test]
    fn joins_slow_down_to_their_cap_whatever_the_corner_angle() {
        let machine = Limits::<2>::new(200.0, 2000.0, 50_000.0).unwrap();
        for angle in [1e-4, 1.0, core::f64::consts::PI] {
            for rate in [1_000.0, 10_000.0] {
                let o = PlanOptions::new().with_corner_angle(angle).with_rate(rate);
                for turn in [1e-3, 0.1, 30.0_f64.to_radians(), 3.0] {
                    let c = polyline(turn);
                    let t = PathTiming::<_, 64, 16>::plan(&c, &machine, &o).unwrap();
                    let zones = t.motion().zones();
                    assert_eq!(zones.len(), 2, "{angle} {rate} {turn}");
                    let join = zones[0];
                    // the velocity step v·|ΔT| = 2v·sin(θ/2) within q·min(a T, j T²) of the
                    // planned limits (¾ of the machine's)
                    let period = 1.0 / rate;
                    let step = 0.5 * (1500.0 * period).min(37_500.0 * period * period);
                    let cap = if turn > angle || turn > core::f64::consts::FRAC_PI_2 {
                        0.0
                    } else {
                        step / (2.0 * (0.5 * turn).sin())
                    };
                    // (a turn of more than 90° is also seen between two samples: a stop)
                    let stops = turn > angle || turn > core::f64::consts::FRAC_PI_2;
                    assert_eq!(join.stops_at_end(), stops, "{angle} {rate} {turn}");
                    let rel = (join.exit_cap() - cap).abs() / cap.max(1e-300);
                    assert!(join.exit_cap() == cap || rel < 1e-9, "{}", join.exit_cap());
                    assert!(
                        join.v_end() <= cap * (1.0 + 1e-12) && zones[1].v_start() == join.v_end(),
                        "{angle} {rate} {turn}: {} {cap} {}",
                        join.v_end(),
                        zones[1].v_start()
                    );
                }
            }
        }
        // a straight polyline: one zone at full speed
        let straight = polyline(0.0);
        let t = PathTiming::<_, 64, 16>::scurve(&straight, &machine).unwrap();
        assert_eq!(t.motion().zones().len(), 1);
    }

    #[test]
    fn cusp_inside_a_piece_stops_the_motion() {
        // c(u) = (20u − 25u², 0): out to x = 4 at u = 0.4 (where c' = 0), back to x = −5
        let c = Bezier::new([[0.0, 0.0], [10.0, 0.0], [-5.0, 0.0]]).unwrap();
        let limits = Limits::<2>::new(200.0, 2000.0, 50_000.0).unwrap();
        let t = PathTiming::<_, 128, 16>::scurve(&c, &limits).unwrap();
        assert!((t.length() - 13.0).abs() < 1e-8);
        let zones = t.motion().zones();
        let stop = zones.iter().find(|z| z.stops_at_end()).expect("a stop");
        assert_eq!(stop.v_end(), 0.0);
        // the motion stands still at the turn: at rest at u = 0.4, x = 4
        let at = stop.phases().last().map(|p| p.end()).unwrap();
        let st = t.motion().state(at);
        assert!(
            (st.s - stop.end()).abs() < 1e-9 && st.v.abs() < 1e-9,
            "{st:?}"
        );
        let (u, du) = t.param(at);
        assert!((u - 0.4).abs() < 1e-12 && du.abs() < 1e-6, "{u} {du}");
        assert!((c.eval(u)[0] - 4.0).abs() < 1e-12);
        // (the table's arc length there is within its interpolation error of 4)
        assert!((stop.end() - 4.0).abs() < 1e-3, "{}", stop.end());
        // a cubic whose tangent reverses twice: two stops
        let c = Bezier::new([[0.0, 0.0], [30.0, 0.0], [-10.0, 0.0], [20.0, 0.0]]).unwrap();
        let t = PathTiming::<_, 128, 64>::scurve(&c, &limits).unwrap();
        let stops = t
            .motion()
            .zones()
            .iter()
            .filter(|z| z.stops_at_end())
            .count();
        assert_eq!(stops, 2);
        // an S-bend whose tangent turns without reversing does not stop
        let c = Bezier::new([[0.0, 0.0], [30.0, 0.0], [-10.0, 10.0], [20.0, 10.0]]).unwrap();
        let t = PathTiming::<_, 128, 256>::scurve(&c, &limits).unwrap();
        assert!(t.motion().zones().iter().all(|z| !z.stops_at_end()));
    }

    #[test]
    fn too_long_at_the_plans_rate() {
        // 50 units at 10⁻³ units/s: 5·10⁴ s, 5·10⁷ ticks at 1 kHz, 5·10⁹ at 100 kHz
        let c = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).unwrap();
        let l = Limits::<2>::new(1e-3, 1.0, 1.0).unwrap();
        let o = PlanOptions::new();
        assert!(PathTiming::<_, 16, 4>::plan(&c, &l, &o).is_ok());
        let fast = o.with_rate(100_000.0);
        assert!(matches!(
            PathTiming::<_, 16, 4>::plan(&c, &l, &fast),
            Err(Error::TooLong)
        ));
        // a velocity limit so small that no rate could play it
        let l = Limits::<2>::new(1.5e-304, 2000.0, 50_000.0).unwrap();
        assert!(matches!(
            PathTiming::<_, 16, 4>::scurve(&c, &l),
            Err(Error::TooLong)
        ));
        assert!(matches!(
            PathTiming::<_, 16, 4>::plan(&c, &l, &o.with_rate(f64::NAN)),
            Err(Error::InvalidRate)
        ));
    }

    #[test]
    fn jerk_phases_are_at_least_sixteen_ticks() {
        let c = Bezier::new([[0.0, 0.0], [30.0, 40.0]]).unwrap();
        let l = Limits::<2>::new(200.0, 2000.0, 1e14).unwrap();
        for rate in [100.0, 1_000.0, 100_000.0] {
            let o = PlanOptions::new().with_rate(rate);
            let t = PathTiming::<_, 16, 4>::plan(&c, &l, &o).unwrap();
            let z = t.motion().zones()[0];
            assert_eq!(z.a_limit(), 1500.0);
            assert_eq!(z.j_limit(), 1500.0 * rate / 16.0);
            // the first jerk phase raises a to a_z in 16 ticks (at 100 Hz the line is too
            // short to reach a_z: a shorter triangle of lower acceleration)
            let first = t.motion().phases().next().unwrap();
            let ticks = first.duration * rate;
            assert!(
                (ticks - 16.0).abs() < 1e-9 || (rate == 100.0 && ticks < 16.0),
                "{ticks}"
            );
        }
    }

    /// Zones `(end, v_limit, a_limit, j_limit)` from arc length 0, filled with or without
    /// the transitions; the duration.
    fn zones_of(spec: &[(f64, f64, f64, f64)], carry: bool) -> (StdVec<ProfileZone>, f64) {
        let mut start = 0.0;
        let mut zones: StdVec<ProfileZone> = spec
            .iter()
            .map(|&(end, v, a, j)| {
                let z = ProfileZone::new(start, end, v, a, j);
                start = end;
                z
            })
            .collect();
        if carry {
            fill_zones(&mut zones);
        } else {
            double_s_zones(&mut zones);
        }
        let t = zones.last().map_or(0.0, ProfileZone::t_end);
        (zones, t)
    }

    #[test]
    fn a_speed_change_through_a_boundary_is_one_double_s() {
        // Two zones of the same limits: the fastest motion is the one double S over both;
        // with zero acceleration at the boundary (inside the first speed change) it is
        // slower.
        let single = MotionProfile::<1>::scurve(10.0, 2.0, 4.0, 16.0).unwrap();
        let rising = [(0.5, 2.0, 4.0, 16.0), (10.0, 2.0, 4.0, 16.0)];
        let falling = [(9.5, 2.0, 4.0, 16.0), (10.0, 2.0, 4.0, 16.0)];
        for spec in [rising, falling] {
            let (zones, t) = zones_of(&spec, true);
            let (_, t_flat) = zones_of(&spec, false);
            assert!(
                (t - single.duration()).abs() < 1e-12,
                "{t} vs {}",
                single.duration()
            );
            assert!(t_flat > t + 0.05, "{t_flat} vs {t}");
            // the boundary is passed with acceleration
            let a = zones[1].phases()[0].a0;
            assert!(a.abs() > 1.0, "{a}");
        }
    }

    #[test]
    fn transitions_keep_every_zone_limit_and_are_continuous() {
        let mut rng = crate::online::testing::Rng(7);
        let mut carried = 0;
        for case in 0..300 {
            let n = 2 + case % 7;
            let mut end = 0.0;
            let spec: StdVec<_> = (0..n)
                .map(|_| {
                    end += rng.range(0.05, 3.0);
                    let v = rng.range(0.5, 3.0);
                    (end, v, rng.range(1.0, 8.0), rng.range(5.0, 50.0))
                })
                .collect();
            let (zones, t) = zones_of(&spec, true);
            let (_, t_flat) = zones_of(&spec, false);
            assert!(t <= t_flat, "case {case}: {t} > {t_flat}");
            carried += usize::from(t < t_flat - 1e-9);
            check_zones(&zones, end, case);
        }
        // (most of the others rise into a zone whose lower limit the faster motion would pass)
        assert!(carried > 50, "{carried} of 300 cases faster");
    }

    /// Every phase continues the previous one in `s`, `v`, `a` and time, keeps its zone's
    /// limits (sampled), and the motion ends at `length` at rest.
    fn check_zones(zones: &[ProfileZone], length: f64, case: usize) {
        let mut prev: Option<Phase> = None;
        for z in zones {
            for ph in z.phases() {
                if let Some(p) = prev {
                    let end = p.local(p.duration);
                    let tol = 1e-9 * (1.0 + end.s);
                    assert!((ph.t0 - p.end()).abs() < 1e-12, "case {case}: time");
                    assert!((ph.s0 - end.s).abs() < tol, "case {case}: s");
                    assert!((ph.v0 - end.v).abs() < 1e-9, "case {case}: v");
                    assert!((ph.a0 - end.a).abs() < 1e-9, "case {case}: a");
                }
                for k in 0..=20 {
                    let st = ph.local(ph.duration * f64::from(k) / 20.0);
                    let ok = st.v >= -1e-12
                        && st.v <= z.v_limit * (1.0 + 1e-9)
                        && st.a.abs() <= z.a_limit * (1.0 + 1e-9)
                        && st.j.abs() <= z.j_limit
                        && st.s >= z.start - 1e-9
                        && st.s <= z.end + 1e-9;
                    assert!(ok, "case {case}: {st:?} in {z:?}");
                }
                prev = Some(*ph);
            }
        }
        let last = prev.unwrap();
        let end = last.local(last.duration);
        assert!(
            (end.s - length).abs() < 1e-9 * length,
            "case {case}: {end:?}"
        );
        assert!(
            end.v.abs() < 1e-9 && end.a.abs() < 1e-9,
            "case {case}: {end:?}"
        );
    }
}
