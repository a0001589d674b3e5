//! The modal state of a G-code program and what each line does with it.

use strak_curves::{Plane, Turn};
use strak_trajectory::{Move, Shape};

use crate::error::{ErrorKind, GcodeError};
use crate::line::{At, Code, Ignored, Line};

/// Millimetres per inch (`G20`).
const MM_PER_INCH: f64 = 25.4;

/// The motion mode (modal group 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Motion {
    /// `G0`: at the machine's limits.
    Rapid,
    /// `G1`: a line at the feed.
    Linear,
    /// `G2`: a clockwise arc or helix.
    Clockwise,
    /// `G3`: a counter-clockwise arc or helix.
    CounterClockwise,
    /// `G5`: a cubic Bézier in the XY plane.
    Cubic,
}

/// How the path passes corners (`G61`, `G64`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PathMode {
    /// `G61` (and `G61.1`): an exact stop at every corner.
    ExactStop,
    /// `G64`: corners blended within the tolerance `P` (machine units), or within the
    /// machine's own tolerance without `P`.
    Blend(Option<f64>),
}

/// What a line asks the machine to do.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Action<const D: usize> {
    /// Nothing moves (comments, modal codes, ignored codes, `G92`).
    None,
    /// A move to machine coordinates.
    Move(Move<D>),
    /// `G4`: stand still for this many seconds.
    Dwell(f64),
}

/// What a line of G-code does: its action and, where it sets one, the path mode from there
/// on.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Block<const D: usize> {
    /// What moves.
    pub action: Action<D>,
    /// The path mode the line sets (`G61`, `G64`), applying to this line's move on.
    pub path_mode: Option<PathMode>,
}

/// The plane of arcs (`G17`, `G18`, `G19`): the letters of its first and second axis and
/// of their centre offsets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct ArcPlane {
    axes: [u8; 2],
    offsets: [u8; 2],
}

const G17: ArcPlane = ArcPlane {
    axes: *b"XY",
    offsets: *b"IJ",
};
const G18: ArcPlane = ArcPlane {
    axes: *b"ZX",
    offsets: *b"KI",
};
const G19: ArcPlane = ArcPlane {
    axes: *b"YZ",
    offsets: *b"JK",
};

/// A G-code reader for a machine with `D` axes: the modal state of the program (motion
/// mode, absolute or incremental distances, units, arc plane, feed, position, `G92`
/// offsets) and the codes it ignored. Each line read ([`read_line`](Self::read_line))
/// returns what it does ([`Block`]) in the machine's units (millimetres: inch programs
/// `G20` are converted) and axis order, its feed in units per second.
///
/// A line (`G0`, `G1`) to where the machine already is moves nothing ([`Action::None`]).
///
/// Codes read: `G0`, `G1`; `G2`, `G3` with `I J K` (offsets from the start, or absolute with
/// `G90.1`) or `R` (negative for the longer arc), in the planes `G17`, `G18`, `G19`, with
/// the other axes moving along (helices), full circles with `I J K`; `G5` (cubic Bézier:
/// `I J` from the start to the first control point, `P Q` from the end to the second; `I J`
/// may be left out after a `G5`, mirroring its `P Q`); `G4 P` (dwell, seconds); `G20`,
/// `G21`; `G90`, `G91`; `G90.1`, `G91.1`; `G92`, `G92.1`; `G61`, `G61.1`, `G64 P`; `G80`;
/// `F` (units per minute, modal); the axes the machine has of `X Y Z A B C E U V W`; `N`;
/// `M82`/`M83` (printers' absolute and relative `E`: with `M83` `E` is incremental whatever
/// `G90`/`G91` say).
/// `M`, `T`, `S`, other letters and other G codes are counted in [`ignored`](Self::ignored)
/// and do nothing.
///
/// ```
/// use strak_gcode::{Action, Reader};
/// use strak_trajectory::Move;
/// let mut reader = Reader::new(*b"XYZE")?;
/// reader.read_line(b"G21 G90 ; millimetres, absolute")?;
/// let block = reader.read_line(b"G1 X10 Y5 E0.4 F1200")?;
/// assert_eq!(block.action, Action::Move(Move::line([10.0, 5.0, 0.0, 0.4]).with_feed(20.0)));
/// reader.read_line(b"M104 S200")?; // ignored, counted
/// assert_eq!(reader.ignored().kinds().len(), 2); // M104 and S
/// # Ok::<(), strak_gcode::GcodeError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Reader<const D: usize> {
    axes: [u8; D],
    arc_tolerance: f64,
    line: u32,
    modal: Modal<D>,
    ignored: Ignored,
}

/// The modal state a line reads and changes (taken over only when the line has no error).
#[derive(Clone, Copy, Debug)]
struct Modal<const D: usize> {
    motion: Option<Motion>,
    incremental: bool,
    /// `M83`: `E` incremental whatever `G90`/`G91` say (`M82`: as they say).
    e_relative: bool,
    arc_absolute: bool,
    inch: bool,
    plane: ArcPlane,
    /// The feed in program units per minute.
    feed: Option<f64>,
    /// Machine coordinates.
    position: [f64; D],
    /// `G92`: program coordinate = machine coordinate − offset.
    offset: [f64; D],
    /// The last `G5`'s `P Q` (machine units), for a `G5` without `I J`.
    last_pq: Option<[f64; 2]>,
}

/// The G codes of one line, each group's at most once, with their columns.
#[derive(Clone, Copy, Debug, Default)]
struct Codes {
    motion: Option<(Option<Motion>, u32)>,
    plane: Option<ArcPlane>,
    incremental: Option<bool>,
    arc_absolute: Option<bool>,
    inch: Option<bool>,
    path: Option<(bool, u32)>,
    dwell: Option<u32>,
    /// `G92` (true) or `G92.1` (false).
    set_position: Option<bool>,
}

/// A modal group of the codes a reader acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Group {
    Motion(Option<Motion>),
    Plane(ArcPlane),
    Distance(bool),
    ArcDistance(bool),
    Units(bool),
    /// `G61`/`G61.1` (exact stop: true) or `G64`.
    Path(bool),
    Dwell,
    SetPosition(bool),
}

/// The group and meaning of the G code `tenths` (`None`: ignored).
fn group(tenths: u32) -> Option<Group> {
    Some(match tenths {
        0 => Group::Motion(Some(Motion::Rapid)),
        10 => Group::Motion(Some(Motion::Linear)),
        20 => Group::Motion(Some(Motion::Clockwise)),
        30 => Group::Motion(Some(Motion::CounterClockwise)),
        50 => Group::Motion(Some(Motion::Cubic)),
        800 => Group::Motion(None),
        40 => Group::Dwell,
        170 => Group::Plane(G17),
        180 => Group::Plane(G18),
        190 => Group::Plane(G19),
        200 => Group::Units(true),
        210 => Group::Units(false),
        610 | 611 => Group::Path(true),
        640 => Group::Path(false),
        900 => Group::Distance(false),
        910 => Group::Distance(true),
        901 => Group::ArcDistance(true),
        911 => Group::ArcDistance(false),
        920 => Group::SetPosition(true),
        921 => Group::SetPosition(false),
        _ => return None,
    })
}

impl Codes {
    /// Files the code of `group` at `column`; a second code of its group is an error.
    fn take(&mut self, group: Group, column: u32) -> Result<(), ErrorKind> {
        fn once<T>(slot: &mut Option<T>, value: T) -> Result<(), ErrorKind> {
            if slot.is_some() {
                return Err(ErrorKind::Repeated);
            }
            *slot = Some(value);
            Ok(())
        }
        match group {
            Group::Motion(m) => once(&mut self.motion, (m, column)),
            Group::Plane(p) => once(&mut self.plane, p),
            Group::Distance(i) => once(&mut self.incremental, i),
            Group::ArcDistance(a) => once(&mut self.arc_absolute, a),
            Group::Units(inch) => once(&mut self.inch, inch),
            Group::Path(exact) => once(&mut self.path, (exact, column)),
            Group::Dwell => once(&mut self.dwell, column),
            Group::SetPosition(set) => once(&mut self.set_position, set),
        }
    }
}

/// The axis letters a machine may have.
const AXIS_LETTERS: &[u8] = b"XYZABCEUVW";

impl<const D: usize> Reader<D> {
    /// A reader for a machine with the axes `axes` (letters of `X Y Z A B C E U V W`, each
    /// at most once, in the order of the moves' coordinates), at its origin, in
    /// millimetres, absolute distances, the XY plane, no motion mode and no feed, with an
    /// arc tolerance of 0.002 mm.
    ///
    /// # Errors
    /// [`ErrorKind::UnknownAxis`] (line 0, the column of the letter in `axes`) for a letter
    /// that is no axis or comes twice.
    ///
    /// ```
    /// use strak_gcode::{ErrorKind, Reader};
    /// assert!(Reader::new(*b"XYZ").is_ok());
    /// assert_eq!(Reader::new(*b"XYX").unwrap_err().kind, ErrorKind::UnknownAxis);
    /// ```
    pub fn new(axes: [u8; D]) -> Result<Self, GcodeError> {
        for (i, a) in axes.iter().enumerate() {
            if !AXIS_LETTERS.contains(a) || axes[..i].contains(a) {
                return Err(GcodeError {
                    line: 0,
                    column: u32::try_from(i + 1).unwrap_or(u32::MAX),
                    kind: ErrorKind::UnknownAxis,
                });
            }
        }
        Ok(Reader {
            axes,
            arc_tolerance: 0.002,
            line: 0,
            modal: Modal {
                motion: None,
                incremental: false,
                e_relative: false,
                arc_absolute: false,
                inch: false,
                plane: G17,
                feed: None,
                position: [0.0; D],
                offset: [0.0; D],
                last_pq: None,
            },
            ignored: Ignored::default(),
        })
    }

    /// The same reader starting at the machine coordinates `position`.
    #[must_use]
    pub fn with_position(mut self, position: [f64; D]) -> Self {
        self.modal.position = position;
        self
    }

    /// The same reader taking an arc's end as on the circle of its start when their
    /// distances from the centre differ by at most `units` (machine units; an `R` arc: when
    /// the chord exceeds the diameter by at most `units`). This is the test the stream's
    /// arcs pass: give the stream the same arc tolerance
    /// ([`StreamOptions::with_arc_tolerance`](strak_trajectory::StreamOptions::with_arc_tolerance))
    /// and every arc the reader takes, the stream takes.
    #[must_use]
    pub fn with_arc_tolerance(mut self, units: f64) -> Self {
        self.arc_tolerance = units;
        self
    }

    /// Where the program has moved the machine (machine coordinates).
    pub fn position(&self) -> [f64; D] {
        self.modal.position
    }

    /// The lines read.
    pub fn lines(&self) -> u32 {
        self.line
    }

    /// The codes ignored so far.
    pub fn ignored(&self) -> &Ignored {
        &self.ignored
    }

    /// Reads the next line of the program (without its line end, or with it), and returns
    /// what it does. The line's number in errors is the count of lines read.
    ///
    /// # Errors
    /// A [`GcodeError`] naming the line and the column of the word at fault; the reader's
    /// state is then as before the line (the line is counted).
    pub fn read_line(&mut self, text: &[u8]) -> Result<Block<D>, GcodeError> {
        self.line = self.line.saturating_add(1);
        let fail = |(column, kind)| GcodeError {
            line: self.line,
            column,
            kind,
        };
        let line = Line::read(text, &self.axes).map_err(fail)?;
        let mut codes = Codes::default();
        let mut unknown = heapless::Vec::<Code, 8>::new();
        for &(tenths, column) in &line.codes {
            match group(tenths) {
                Some(g) => codes.take(g, column).map_err(|k| fail((column, k)))?,
                None => {
                    let _ = unknown.push(Code {
                        letter: b'G',
                        tenths,
                    });
                }
            }
        }
        let mut modal = self.modal;
        let e_mode = |c: &Code| c.letter == b'M' && (c.tenths == 820 || c.tenths == 830);
        if let Some(c) = line.ignored.iter().rev().find(|c| e_mode(c)) {
            modal.e_relative = c.tenths == 830;
        }
        let block = self.block(&mut modal, &codes, &line).map_err(fail)?;
        self.modal = modal;
        for code in line.ignored.iter().filter(|c| !e_mode(c)).chain(&unknown) {
            self.ignored.count(*code);
        }
        Ok(block)
    }

    /// What `line` with its `codes` does, changing `m`.
    fn block(
        &self,
        m: &mut Modal<D>,
        codes: &Codes,
        line: &Line<D>,
    ) -> Result<Block<D>, (u32, ErrorKind)> {
        m.inch = codes.inch.unwrap_or(m.inch);
        m.incremental = codes.incremental.unwrap_or(m.incremental);
        m.arc_absolute = codes.arc_absolute.unwrap_or(m.arc_absolute);
        m.plane = codes.plane.unwrap_or(m.plane);
        if let Some((f, column)) = line.feed {
            if f <= 0.0 {
                return Err((column, ErrorKind::NoFeed));
            }
            m.feed = Some(f);
        }
        let scale = if m.inch { MM_PER_INCH } else { 1.0 };
        let path_mode = codes.path.map(|(exact, _)| {
            if exact {
                PathMode::ExactStop
            } else {
                PathMode::Blend(line.param(b'P').map(|(p, _)| p * scale))
            }
        });
        let block = |action| Block { action, path_mode };
        if let Some(column) = codes.dwell {
            return match line.param(b'P') {
                Some((p, _)) if p >= 0.0 => Ok(block(Action::Dwell(p))),
                _ => Err((column, ErrorKind::BadDwell)),
            };
        }
        if let Some(set) = codes.set_position {
            for i in 0..D {
                m.offset[i] = match (set, line.axes[i]) {
                    (true, Some((v, _))) => m.position[i] - v * scale,
                    (true, None) => m.offset[i],
                    (false, _) => 0.0,
                };
            }
            return Ok(block(Action::None));
        }
        if let Some((motion, _)) = codes.motion {
            m.motion = motion;
        }
        let circle = matches!(m.motion, Some(Motion::Clockwise | Motion::CounterClockwise))
            && m.plane.offsets.iter().any(|&o| line.param(o).is_some());
        if !(line.moves_axes() || circle) {
            return Ok(block(Action::None));
        }
        let at = codes.motion.map_or(line.first, |(_, c)| c);
        let motion = m.motion.ok_or((line.first, ErrorKind::NoMotionMode))?;
        let mv = self.motion(m, motion, line, (scale, at))?;
        if mv.shape == Shape::Line && mv.to == m.position {
            return Ok(block(Action::None)); // a line to where the machine is: nothing moves
        }
        m.position = mv.to;
        Ok(block(Action::Move(mv)))
    }

    /// The move of `line` in the mode `motion` from `m`'s position, with the program's
    /// units `scale` (millimetres per unit); `at` is the column errors name.
    fn motion(
        &self,
        m: &mut Modal<D>,
        motion: Motion,
        line: &Line<D>,
        (scale, at): (f64, u32),
    ) -> Result<Move<D>, (u32, ErrorKind)> {
        let relative = |i: usize| m.incremental || (m.e_relative && self.axes[i] == b'E');
        let to: [f64; D] = core::array::from_fn(|i| match line.axes[i] {
            Some((v, _)) if relative(i) => m.position[i] + v * scale,
            Some((v, _)) => v * scale + m.offset[i],
            None => m.position[i],
        });
        if motion == Motion::Rapid {
            m.last_pq = None;
            return Ok(Move::line(to));
        }
        let feed = m.feed.ok_or((at, ErrorKind::NoFeed))? * scale / 60.0;
        let shape = match motion {
            Motion::Clockwise | Motion::CounterClockwise => {
                m.last_pq = None;
                self.arc(m, motion, line, (&to, scale))
                    .map_err(|k| (at, k))?
            }
            Motion::Cubic => self.cubic(m, line, (&to, scale)).map_err(|k| (at, k))?,
            Motion::Rapid | Motion::Linear => {
                m.last_pq = None;
                Shape::Line
            }
        };
        Ok(Move::new(to, shape).with_feed(feed))
    }

    /// The machine's index of the axis `letter`.
    fn index(&self, letter: u8) -> Result<usize, ErrorKind> {
        self.axes
            .iter()
            .position(|&a| a == letter)
            .ok_or(ErrorKind::UnknownAxis)
    }

    /// The arc (`G2`, `G3`) of `line` from `m`'s position to `to`, checked: its end on the
    /// circle of its start within the arc tolerance.
    fn arc(
        &self,
        m: &Modal<D>,
        motion: Motion,
        line: &Line<D>,
        (to, scale): (&[f64; D], f64),
    ) -> Result<Shape<D>, ErrorKind> {
        let (a, b) = (self.index(m.plane.axes[0])?, self.index(m.plane.axes[1])?);
        let plane = Plane {
            first: a,
            second: b,
        };
        let turn = if motion == Motion::Clockwise {
            Turn::Clockwise
        } else {
            Turn::CounterClockwise
        };
        let from = m.position;
        let [oa, ob] = m.plane.offsets.map(|o| line.param(o));
        let chord = libm::hypot(to[a] - from[a], to[b] - from[b]);
        if let Some((r, _)) = line.param(b'R') {
            if oa.is_some() || ob.is_some() {
                return Err(ErrorKind::ArcWithoutCenter);
            }
            let radius = r * scale;
            if chord == 0.0 {
                return Err(ErrorKind::ArcFullCircleWithRadius);
            }
            if chord > 2.0 * radius.abs() + self.arc_tolerance {
                return Err(ErrorKind::ArcRadiusMismatch);
            }
            return Ok(Shape::ArcRadius {
                radius,
                plane,
                turn,
            });
        }
        if oa.is_none() && ob.is_none() {
            return Err(ErrorKind::ArcWithoutCenter);
        }
        let center = |o: Option<At>, i: usize| match o {
            Some((v, _)) if m.arc_absolute => v * scale + m.offset[i],
            Some((v, _)) => from[i] + v * scale,
            None => from[i],
        };
        let center = [center(oa, a), center(ob, b)];
        let r0 = libm::hypot(from[a] - center[0], from[b] - center[1]);
        let r1 = libm::hypot(to[a] - center[0], to[b] - center[1]);
        if !(r0 > 0.0 && (r1 - r0).abs() <= self.arc_tolerance) {
            return Err(ErrorKind::ArcRadiusMismatch);
        }
        Ok(Shape::ArcCenter {
            center,
            plane,
            turn,
        })
    }

    /// The cubic Bézier (`G5`) of `line` from `m`'s position to `to`, in the XY plane: its
    /// inner control points `start + (I, J)` (or, without `I J`, the last `G5`'s `P Q`
    /// mirrored) and `end + (P, Q)`; the other axes go a third and two thirds of the way.
    fn cubic(
        &self,
        m: &mut Modal<D>,
        line: &Line<D>,
        (to, scale): (&[f64; D], f64),
    ) -> Result<Shape<D>, ErrorKind> {
        let (x, y) = (self.index(b'X')?, self.index(b'Y')?);
        if m.plane != G17 {
            return Err(ErrorKind::BadCubic);
        }
        let (Some((p, _)), Some((q, _))) = (line.param(b'P'), line.param(b'Q')) else {
            return Err(ErrorKind::BadCubic);
        };
        let first = match (line.param(b'I'), line.param(b'J'), m.last_pq) {
            (Some((i, _)), Some((j, _)), _) => [i * scale, j * scale],
            (None, None, Some([p0, q0])) => [-p0, -q0],
            _ => return Err(ErrorKind::BadCubic),
        };
        let from = m.position;
        let mut c1: [f64; D] = core::array::from_fn(|i| from[i] + (to[i] - from[i]) / 3.0);
        let mut c2: [f64; D] = core::array::from_fn(|i| from[i] + 2.0 * (to[i] - from[i]) / 3.0);
        c1[x] = from[x] + first[0];
        c1[y] = from[y] + first[1];
        c2[x] = to[x] + p * scale;
        c2[y] = to[y] + q * scale;
        m.last_pq = Some([p * scale, q * scale]);
        Ok(Shape::Bezier { c1, c2 })
    }
}
