//! The segments of a streamed path: the part of a move between its blends, or a blend; each
//! with its arc length and its frame by arc length (point, unit tangent, curvature vector).

use strak_curves::{
    ParamCurve, ParamCurveDeriv, Point, arc_length, arc_length_between, basis::MonomialCurve,
    param_at_length,
};

use super::arc_map::ArcMap;
use super::blend::Blend;
use super::moves::{MoveCurve, NoCurve, StreamCurve};
use super::ride::Ride;
use crate::error::Error;
use crate::plan::ArcLengths;

/// The relative accuracy of a blend's arc lengths: positions along it within `1e-10` of its
/// length (the adaptive quadrature cannot always reach much closer to the rounding of
/// `f64` within its bounds).
const BLEND_LENGTH_ACCURACY: f64 = 1e-10;

/// What a segment traces.
// A blend's six control points take about as much room as a move for three axes; the lint
// sizes them for no axis.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug)]
enum Trace<const D: usize, C> {
    /// The move `curve` over its parameters `from ..= to`; `offset` is its arc length
    /// before `from`; `map` its arc lengths where they are not proportional to the
    /// parameter (else, or where the map is refused, the move's own inversion).
    Span {
        curve: MoveCurve<D, C>,
        from: f64,
        to: f64,
        offset: f64,
        map: Option<ArcMap>,
    },
    /// A corner blend, over `[0, 1]`, in the monomial basis (Horner's rule evaluates its
    /// derivative in a fifth of de Casteljau's work), with its arc lengths (`None`:
    /// adaptive inversion).
    Blend(MonomialCurve<[f64; D], 6>, Option<ArcMap>),
}

/// A segment of the blended path, placed at the arc length `start` of the whole stream; its
/// last `R` axes ride along ([`Ride`]): the trace holds them at 0, and the segment's frame
/// and derivatives take them from `ride`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment<const D: usize, C = NoCurve<D>, const R: usize = 0> {
    trace: Trace<D, C>,
    ride: [Ride; R],
    /// The arc length of the stream where the segment starts.
    pub(crate) start: f64,
    /// Its arc length.
    pub(crate) length: f64,
    /// Its speed limit (the feeds of the moves it belongs to).
    pub(crate) feed: f64,
}

/// The point of a path at an arc length, its unit tangent `T = dx/ds` and its curvature
/// vector `κN = d²x/ds²`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame<const D: usize> {
    pub(crate) point: [f64; D],
    pub(crate) tangent: [f64; D],
    pub(crate) normal: [f64; D],
}

impl<const D: usize, C: StreamCurve<D>, const R: usize> Segment<D, C, R> {
    /// The part `from ..= to` of the move `curve`, starting at the stream's arc length
    /// `start`, with the speed limit `feed`; a curve move's arc length up to `from` is
    /// `offset` (the other moves' is computed). Its axes riding along have no values yet
    /// ([`with_ride`](Self::with_ride)).
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc length of a curved move does not converge.
    pub(crate) fn span(
        curve: &MoveCurve<D, C>,
        (from, to): (f64, f64),
        start: f64,
        feed: f64,
        offset: f64,
    ) -> Result<Self, Error> {
        let offset = if curve.is_curve() {
            offset
        } else {
            curve.length_to(from)?
        };
        let map = (!curve.has_constant_speed())
            .then(|| ArcMap::new(curve, (from, to)))
            .flatten();
        let length = match &map {
            Some(map) => map.length(),
            None => curve.length_to(to)? - offset,
        };
        let trace = Trace::Span {
            curve: *curve,
            from,
            to,
            offset,
            map,
        };
        Ok(Segment {
            trace,
            ride: [Ride::default(); R],
            start,
            length,
            feed,
        })
    }

    /// The corner blend `blend`, starting at the stream's arc length `start`, with the
    /// speed limit `feed`.
    ///
    /// # Errors
    /// [`Error::Curve`] when its arc length does not converge.
    pub(crate) fn blend(blend: &Blend<D>, start: f64, feed: f64) -> Result<Self, Error> {
        let curve = blend.curve().to_monomial()?;
        let map = ArcMap::new(&curve, (0.0, 1.0));
        let length = match &map {
            Some(map) => map.length(),
            None => arc_length(&curve, BLEND_LENGTH_ACCURACY * blend.trim())?,
        };
        Ok(Segment {
            trace: Trace::Blend(curve, map),
            ride: [Ride::default(); R],
            start,
            length,
            feed,
        })
    }

    /// Gives the axes riding along the values `(e, de/ds)` at the segment's start and end,
    /// each axis's pair in turn: on a span the values alone count (the axis goes in
    /// proportion to the arc length from the start value to the end value); on a blend the
    /// rates count too (see [`Ride`]).
    pub(crate) fn with_ride(mut self, ends: [((f64, f64), (f64, f64)); R]) -> Self {
        for (ride, ((e0, m0), (e1, m1))) in self.ride.iter_mut().zip(ends) {
            *ride = match &self.trace {
                Trace::Span { .. } => Ride::Linear { e0, e1 },
                Trace::Blend(b, _) => {
                    let sigma = |u: f64| {
                        let (d1, d2) = (b.deriv(u, 1), b.deriv(u, 2));
                        let s = d1.norm();
                        (s, if s > 0.0 { d1.dot(d2) / s } else { 0.0 })
                    };
                    let ((s0, s0d), (s1, s1d)) = (sigma(0.0), sigma(1.0));
                    Ride::hermite((e0, m0 * s0, m0 * s0d), (e1, m1 * s1, m1 * s1d))
                }
            };
        }
        self
    }

    /// The segment of a move of the riding axes alone: it traces them itself (the other
    /// axes stand still).
    pub(crate) fn riding_alone(mut self) -> Self {
        self.ride = [Ride::Alone; R];
        self
    }

    /// Whether the segment is a move of the riding axes alone.
    pub(crate) fn rides_alone(&self) -> bool {
        self.ride.first() == Some(&Ride::Alone)
    }

    /// The value and rate `de/ds` of each axis riding along at the segment's end (a move
    /// of the riding axes alone ends at rest: no rate).
    pub(crate) fn ride_end(&self) -> [(f64, f64); R] {
        let (_, hi) = ParamCurve::domain(self);
        let (end, sigma) = (self.trace_deriv(hi, 0), self.trace_deriv(hi, 1).norm());
        let mut out = [(0.0, 0.0); R];
        for (i, (slot, r)) in out.iter_mut().zip(&self.ride).enumerate() {
            *slot = match r {
                Ride::Linear { .. } => r.along(self.length, self.length),
                Ride::Quintic(_) if sigma > 0.0 => (r.poly(1.0, 0), r.poly(1.0, 1) / sigma),
                Ride::Quintic(_) => (r.poly(1.0, 0), 0.0),
                Ride::Alone => (end[D - R + i], 0.0),
            };
        }
        out
    }

    /// The `k`-th derivative of what the segment traces (its axes riding along at 0).
    fn trace_deriv(&self, u: f64, k: usize) -> [f64; D] {
        match &self.trace {
            Trace::Span { curve, .. } => curve.deriv(u, k),
            Trace::Blend(b, _) => b.deriv(u, k),
        }
    }

    /// The arc length of the stream where the segment ends.
    pub(crate) fn end(&self) -> f64 {
        self.start + self.length
    }

    /// Whether its speed limits are the same everywhere: a line, circle or helix, whose
    /// curvature and torsion are constant.
    pub(crate) fn uniform(&self) -> bool {
        matches!(&self.trace, Trace::Span { curve, .. } if curve.has_constant_speed())
    }

    /// The parameter at the arc length `s` from the segment's start (clamped to it; its ends
    /// exactly).
    fn param(&self, s: f64) -> Result<f64, Error> {
        let (lo, hi) = ParamCurve::domain(self);
        if s <= 0.0 {
            return Ok(lo);
        }
        if s >= self.length {
            return Ok(hi);
        }
        match &self.trace {
            Trace::Span {
                curve,
                map: Some(map),
                ..
            } => Ok(map.param(curve, s)),
            Trace::Span {
                curve,
                from,
                to,
                offset,
                map: None,
            } => Ok(curve.param_at(offset + s)?.clamp(*from, *to)),
            Trace::Blend(b, Some(map)) => Ok(map.param(b, s)),
            Trace::Blend(b, None) => {
                Ok(param_at_length(b, s, BLEND_LENGTH_ACCURACY * self.length)?)
            }
        }
    }

    /// The frame at the stream's arc length `s` (clamped to the segment): `T = c'/σ` and
    /// `κN = (c'' − (c'·c''/σ²)·c')/σ²` with `σ = |c'|` (do Carmo, *Differential Geometry
    /// of Curves and Surfaces*, §1-5); at a point where `c' = 0` (a cusp, passed at rest)
    /// both are zero.
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc-length inversion does not converge.
    pub(crate) fn frame(&self, s: f64) -> Result<Frame<D>, Error> {
        let local = self.local(s);
        let u = self.param(local)?;
        let (d1, d2) = (self.trace_deriv(u, 1), self.trace_deriv(u, 2));
        let speed2 = d1.dot(d1);
        let mut frame = Frame {
            point: self.trace_deriv(u, 0),
            tangent: [0.0; D],
            normal: [0.0; D],
        };
        if speed2 > 0.0 {
            let sigma = libm::sqrt(speed2);
            let along = d1.dot(d2) / speed2;
            frame.tangent = d1.times(1.0 / sigma);
            frame.normal = d2.minus(d1.times(along)).times(1.0 / speed2);
        }
        self.ride_frame(&mut frame, (u, local), (d1, d2));
        Ok(frame)
    }

    /// The point of [`Self::frame`] alone, to the bit: the trace's point with the axes
    /// riding along at their values.
    ///
    /// # Errors
    /// [`Error::Curve`] when the arc-length inversion does not converge.
    pub(crate) fn point(&self, s: f64) -> Result<[f64; D], Error> {
        let local = self.local(s);
        let u = self.param(local)?;
        let mut point = self.trace_deriv(u, 0);
        for (x, r) in point[D - R..].iter_mut().zip(&self.ride) {
            *x = match r {
                Ride::Alone => continue,
                Ride::Linear { .. } => r.along(local, self.length).0,
                Ride::Quintic(_) => r.poly(u, 0),
            };
        }
        Ok(point)
    }

    /// The arc length from the segment's start to the stream's arc length `s` (its length
    /// from its end on).
    fn local(&self, s: f64) -> f64 {
        if s >= self.end() {
            self.length
        } else {
            s - self.start
        }
    }

    /// The axes riding along in `frame`, at the parameter `u` and the arc length `local`
    /// from the start, where the trace has the derivatives `d1`, `d2`: `e`, `de/ds` and
    /// `d²e/ds² = (e_uu − e_s·σ')/σ²`.
    fn ride_frame(
        &self,
        frame: &mut Frame<D>,
        (u, local): (f64, f64),
        (d1, d2): ([f64; D], [f64; D]),
    ) {
        let first = D - R;
        for (i, r) in self.ride.iter().enumerate() {
            let (x, t, n) = match r {
                Ride::Alone => continue,
                Ride::Linear { .. } => {
                    let (e, m) = r.along(local, self.length);
                    (e, m, 0.0)
                }
                Ride::Quintic(_) => {
                    let sigma = d1.norm();
                    if sigma > 0.0 {
                        let s1 = d1.dot(d2) / sigma;
                        let es = r.poly(u, 1) / sigma;
                        (r.poly(u, 0), es, (r.poly(u, 2) - es * s1) / (sigma * sigma))
                    } else {
                        (r.poly(u, 0), 0.0, 0.0)
                    }
                }
            };
            frame.point[first + i] = x;
            frame.tangent[first + i] = t;
            frame.normal[first + i] = n;
        }
    }
}

/// The segment's own arc lengths, by which the speed-limit sampling places its zones (where
/// an adaptive length does not converge, the parameter's share of the length stands in: it
/// only moves a zone boundary).
impl<const D: usize, C: StreamCurve<D>, const R: usize> ArcLengths for Segment<D, C, R> {
    fn domain(&self) -> (f64, f64) {
        ParamCurve::domain(self)
    }

    fn length(&self) -> f64 {
        self.length
    }

    fn length_at(&self, u: f64) -> f64 {
        let (lo, hi) = ParamCurve::domain(self);
        let share = || self.length * ((u - lo) / (hi - lo)).clamp(0.0, 1.0);
        match &self.trace {
            Trace::Span {
                curve,
                map: Some(map),
                ..
            } => map.length_at(curve, u),
            Trace::Span { curve, offset, .. } => {
                curve.length_to(u).map_or_else(|_| share(), |s| s - offset)
            }
            Trace::Blend(b, Some(map)) => map.length_at(b, u),
            Trace::Blend(b, None) => {
                arc_length_between(b, 0.0, u, BLEND_LENGTH_ACCURACY * self.length)
                    .unwrap_or_else(|_| share())
            }
        }
    }

    fn param_at(&self, s: f64) -> f64 {
        let (lo, hi) = ParamCurve::domain(self);
        self.param(s)
            .unwrap_or_else(|_| lo + (hi - lo) * (s / self.length).clamp(0.0, 1.0))
    }

    /// A segment's arc length at a parameter costs a quadrature: the sampling integrates
    /// its samples' speeds instead.
    fn lengths_by_samples(&self) -> bool {
        true
    }
}

impl<const D: usize, C: StreamCurve<D>, const R: usize> ParamCurve for Segment<D, C, R> {
    type Point = [f64; D];

    fn domain(&self) -> (f64, f64) {
        match &self.trace {
            Trace::Span { from, to, .. } => (*from, *to),
            Trace::Blend(..) => (0.0, 1.0),
        }
    }

    /// The pieces of a curve move the span crosses (one for the other segments), so that
    /// the speed limits cap its joins of pieces.
    fn piece_count(&self) -> usize {
        match &self.trace {
            Trace::Span {
                curve, from, to, ..
            } => curve.pieces_within((*from, *to)).1,
            Trace::Blend(..) => 1,
        }
    }

    fn piece_domain(&self, i: usize) -> (f64, f64) {
        let (lo, hi) = ParamCurve::domain(self);
        let Trace::Span {
            curve, from, to, ..
        } = &self.trace
        else {
            return (lo, hi);
        };
        let (first, count) = curve.pieces_within((*from, *to));
        let (a, b) = curve.piece_domain(first + i.min(count - 1));
        (a.max(lo), b.min(hi))
    }

    fn eval(&self, u: f64) -> [f64; D] {
        let mut x = self.trace_deriv(u, 0);
        for (i, r) in self.ride.iter().enumerate() {
            x[D - R + i] = match r {
                Ride::Linear { .. } => r.along(self.length_at(u), self.length).0,
                Ride::Quintic(_) => r.poly(u, 0),
                Ride::Alone => continue,
            };
        }
        x
    }
}

/// The derivatives by the parameter, the axes riding along included (what the speed-limit
/// sampling takes their loads from): on a span `e = e₀ + m·s(u)`, so `e_u = m·σ`,
/// `e_uu = m·σ'`, `e_uuu = m·σ''` with `σ = |c'|`, `σ' = c'·c''/σ` and
/// `σ'' = (c''·c'' + c'·c''' − σ'²)/σ`; on a blend the quintic's own.
impl<const D: usize, C: StreamCurve<D>, const R: usize> ParamCurveDeriv for Segment<D, C, R> {
    fn deriv(&self, u: f64, k: usize) -> [f64; D] {
        if k == 0 {
            return self.eval(u);
        }
        let trace = self.trace_deriv(u, k);
        if R == 0 {
            return trace;
        }
        // σ, σ′ or σ″ for k = 1, 2, 3, from the trace's derivatives (the `k`-th at hand).
        let rate = || {
            let d1 = if k == 1 {
                trace
            } else {
                self.trace_deriv(u, 1)
            };
            let sigma = d1.norm();
            if sigma == 0.0 {
                return 0.0;
            }
            let d2 = if k == 2 {
                trace
            } else {
                self.trace_deriv(u, 2)
            };
            let s1 = d1.dot(d2) / sigma;
            match k {
                1 => sigma,
                2 => s1,
                3 => (d2.dot(d2) + d1.dot(trace) - s1 * s1) / sigma,
                _ => 0.0,
            }
        };
        let mut d = trace;
        let mut once = None; // the rate is the same for every riding axis
        for (i, r) in self.ride.iter().enumerate() {
            d[D - R + i] = match r {
                // an axis that stays put has no derivatives: no rate to scale
                Ride::Linear { e0, e1 } if e0 == e1 => 0.0,
                Ride::Linear { .. } => r.slope(self.length) * *once.get_or_insert_with(rate),
                Ride::Quintic(_) => r.poly(u, k),
                Ride::Alone => continue,
            };
        }
        d
    }

    /// [`deriv`](Self::deriv) for `k = 1, 2, 3`, to the bit, with the trace's derivatives
    /// and the rates `σ, σ′, σ″` of the riding axes evaluated once for all three.
    fn deriv_triple(&self, u: f64) -> [[f64; D]; 3] {
        let mut d = [1, 2, 3].map(|k| self.trace_deriv(u, k));
        if R == 0 {
            return d;
        }
        let [d1, d2, d3] = d;
        let rates = || {
            let sigma = d1.norm();
            if sigma == 0.0 {
                return [0.0; 3];
            }
            let s1 = d1.dot(d2) / sigma;
            [sigma, s1, (d2.dot(d2) + d1.dot(d3) - s1 * s1) / sigma]
        };
        let mut once = None;
        for (i, r) in self.ride.iter().enumerate() {
            for (k, dk) in d.iter_mut().enumerate() {
                dk[D - R + i] = match r {
                    Ride::Linear { e0, e1 } if e0 == e1 => 0.0,
                    Ride::Linear { .. } => r.slope(self.length) * once.get_or_insert_with(rates)[k],
                    Ride::Quintic(_) => r.poly(u, k + 1),
                    Ride::Alone => continue,
                };
            }
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::{Junction, Move, junction};

    /// `deriv_triple` equals `deriv` for k = 1, 2, 3 to the bit: on a blend with an axis
    /// riding along as a quintic, on a span with one riding in proportion, one standing
    /// still, and on a move of the riding axes alone.
    #[test]
    fn deriv_triple_is_deriv_to_the_bit() {
        let a = MoveCurve::new([0.0; 4], &Move::<4>::line([10.0, 0.0, 0.0, 0.0]), 0.0).unwrap();
        let b = MoveCurve::new(
            [10.0, 0.0, 0.0, 0.0],
            &Move::line([10.0, 10.0, 0.0, 0.0]),
            0.0,
        )
        .unwrap();
        let Junction::Blend(blend) = junction(&a, &b, 0.1).unwrap() else {
            panic!("a right angle blends")
        };
        let ride = [((1.0, 0.02), (1.3, 0.05)), ((2.0, 0.0), (2.0, 0.0))];
        let blended = Segment::<4, _, 2>::blend(&blend, 3.0, 50.0)
            .unwrap()
            .with_ride(ride);
        let span = Segment::<4, _, 2>::span(&a, (0.0, 0.9), 0.0, 50.0, 0.0).unwrap();
        let segments = [blended, span.with_ride(ride), span.riding_alone()];
        for (i, seg) in segments.iter().enumerate() {
            for k in 0..=20 {
                let (lo, hi) = ParamCurve::domain(seg);
                let u = lo + (hi - lo) * f64::from(k) / 20.0;
                let each = [1, 2, 3].map(|k| seg.deriv(u, k));
                let both = seg.deriv_triple(u);
                for (x, y) in each.iter().flatten().zip(both.iter().flatten()) {
                    assert_eq!(
                        x.to_bits(),
                        y.to_bits(),
                        "segment {i} at {u}: {each:?} {both:?}"
                    );
                }
            }
        }
    }

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        a.minus(b).norm() <= tol
    }

    /// A span of a quarter circle and a blend: lengths, frames against the circle's own
    /// and against differences of the points by arc length.
    #[test]
    fn frames_by_arc_length() {
        let arc = Move::<2>::new(
            [0.0, 2.0],
            crate::stream::Shape::ArcCenter {
                center: [0.0, 0.0],
                plane: strak_curves::Plane::XY,
                turn: strak_curves::Turn::CounterClockwise,
            },
        );
        let curve = MoveCurve::new([2.0, 0.0], &arc, 1e-12).unwrap();
        let seg: Segment<2> = Segment::span(&curve, (0.25, 0.75), 10.0, 100.0, 0.0).unwrap();
        let quarter = core::f64::consts::PI; // of the circle of radius 2
        assert!((seg.length - quarter / 2.0).abs() < 1e-12);
        let f = seg.frame(10.0 + quarter / 4.0).unwrap();
        let r = core::f64::consts::FRAC_1_SQRT_2;
        assert!(close(f.point, [2.0 * r, 2.0 * r], 1e-12), "{f:?}");
        assert!(close(f.tangent, [-r, r], 1e-12));
        assert!(close(f.normal, [-r / 2.0, -r / 2.0], 1e-12)); // κ = 1/2 towards the centre

        let a = MoveCurve::new([0.0, 0.0], &Move::<2>::line([10.0, 0.0]), 0.0).unwrap();
        let b = MoveCurve::new([10.0, 0.0], &Move::line([10.0, 10.0]), 0.0).unwrap();
        let Junction::Blend(blend) = junction(&a, &b, 0.1).unwrap() else {
            panic!("a right angle blends")
        };
        let seg = Segment::<2>::blend(&blend, 3.0, 50.0).unwrap();
        assert!(seg.length > 0.0 && seg.end() == 3.0 + seg.length);
        let h = 1e-4;
        for i in 1..10 {
            let s = 3.0 + seg.length * f64::from(i) / 10.0;
            let (p0, p1, p2) = (
                seg.frame(s - h).unwrap().point,
                seg.frame(s).unwrap(),
                seg.frame(s + h).unwrap().point,
            );
            let tangent = p2.minus(p0).times(0.5 / h);
            let normal = p2.minus(p1.point.times(2.0)).plus(p0).times(1.0 / (h * h));
            assert!(close(tangent, p1.tangent, 1e-7), "{i}");
            assert!(
                close(normal, p1.normal, 1e-4 * (1.0 + p1.normal.norm())),
                "{i}"
            );
        }
        assert!(close(
            seg.frame(3.0).unwrap().point,
            blend.curve().eval(0.0),
            1e-15
        ));
        assert!(close(
            seg.frame(seg.end()).unwrap().point,
            blend.curve().eval(1.0),
            1e-12
        ));
    }
}
