//! The reader, code by code: what each line does, the modal state it keeps, and one test
//! per error.

use strak_curves::{Plane, Turn};
use strak_gcode::{Action, Code, ErrorKind, GcodeError, LineBuffer, PathMode, Reader, lines};
use strak_trajectory::{Limits, Move, Shape, Stream, StreamOptions};

fn reader() -> Reader<4> {
    Reader::new(*b"XYZE").unwrap()
}

/// The move a line reads to (panics for another action).
fn mv(r: &mut Reader<4>, line: &str) -> Move<4> {
    match r.read_line(line.as_bytes()).unwrap().action {
        Action::Move(m) => m,
        other => panic!("{line}: {other:?}"),
    }
}

fn err(r: &mut Reader<4>, line: &str) -> (u32, ErrorKind) {
    let e: GcodeError = r.read_line(line.as_bytes()).unwrap_err();
    (e.column, e.kind)
}

#[test]
fn lines_and_rapids_absolute_and_incremental() {
    let mut r = reader();
    assert_eq!(mv(&mut r, "G0 X10 Y5"), Move::line([10.0, 5.0, 0.0, 0.0]));
    // F is modal, in units per minute: 600 mm/min = 10 mm/s
    assert_eq!(
        mv(&mut r, "G1 Z-1 F600"),
        Move::line([10.0, 5.0, -1.0, 0.0]).with_feed(10.0)
    );
    assert_eq!(
        mv(&mut r, "X12 E0.5"),
        Move::line([12.0, 5.0, -1.0, 0.5]).with_feed(10.0)
    );
    mv(&mut r, "G91 X1 Y-1 E0.25");
    assert_eq!(r.position(), [13.0, 4.0, -1.0, 0.75]);
    assert_eq!(r.read_line(b"G90").unwrap().action, Action::None);
    assert_eq!(r.read_line(b"G1 X13").unwrap().action, Action::None); // already there
    assert_eq!(mv(&mut r, "G0 X0").to, [0.0, 4.0, -1.0, 0.75]);
}

#[test]
fn e_is_relative_after_m83() {
    let mut r = reader();
    mv(&mut r, "G1 X1 E1 F60");
    r.read_line(b"M83").unwrap();
    assert_eq!(mv(&mut r, "G1 X2 E0.5").to, [2.0, 0.0, 0.0, 1.5]);
    assert_eq!(mv(&mut r, "G1 E-1").to, [2.0, 0.0, 0.0, 0.5]);
    r.read_line(b"M82").unwrap();
    assert_eq!(mv(&mut r, "G1 X3 E4").to, [3.0, 0.0, 0.0, 4.0]);
    assert!(r.ignored().kinds().is_empty()); // M82 and M83 are acted on
}

#[test]
fn inches_are_converted_to_millimetres() {
    let mut r = reader();
    let m = mv(&mut r, "G20 G1 X1 Y2 F60");
    assert_eq!(m.to, [25.4, 50.8, 0.0, 0.0]);
    assert_eq!(m.feed, Some(25.4)); // 60 in/min = 1 in/s
    assert_eq!(mv(&mut r, "G21 X1").to, [1.0, 50.8, 0.0, 0.0]);
}

#[test]
fn g92_sets_the_program_coordinates() {
    let mut r = reader();
    mv(&mut r, "G0 X10 Y10");
    assert_eq!(r.read_line(b"G92 X0 E0").unwrap().action, Action::None);
    assert_eq!(r.position(), [10.0, 10.0, 0.0, 0.0]);
    assert_eq!(mv(&mut r, "G1 X5 E2 F60").to, [15.0, 10.0, 0.0, 2.0]);
    r.read_line(b"G92.1").unwrap();
    assert_eq!(mv(&mut r, "G1 X5").to, [5.0, 10.0, 0.0, 2.0]);
}

#[test]
fn arcs_in_each_plane_with_centres_and_radii() {
    let mut r = reader();
    mv(&mut r, "G0 X10 Y0");
    let m = mv(&mut r, "G3 X0 Y10 I-10 J0 F1200");
    let xy = Plane::XY;
    let ccw = Turn::CounterClockwise;
    assert_eq!(
        m.shape,
        Shape::ArcCenter {
            center: [0.0, 0.0],
            plane: xy,
            turn: ccw
        }
    );
    assert_eq!(m.feed, Some(20.0));
    // a helix: Z and E move along
    let m = mv(&mut r, "G2 X10 Y0 Z-2 E1 I0 J-10");
    assert_eq!(m.to, [10.0, 0.0, -2.0, 1.0]);
    let cw = Turn::Clockwise;
    assert_eq!(
        m.shape,
        Shape::ArcCenter {
            center: [0.0, 0.0],
            plane: xy,
            turn: cw
        }
    );
    // the radius form, negative for the longer arc
    let m = mv(&mut r, "G2 X0 Y10 R-10");
    assert_eq!(
        m.shape,
        Shape::ArcRadius {
            radius: -10.0,
            plane: xy,
            turn: cw
        }
    );
    // G18 (ZX: K then I) and G19 (YZ: J then K)
    mv(&mut r, "G0 X0 Y0 Z0");
    let m = mv(&mut r, "G18 G2 X10 Z0 I5 K0");
    let zx = Plane {
        first: 2,
        second: 0,
    };
    assert_eq!(
        m.shape,
        Shape::ArcCenter {
            center: [0.0, 5.0],
            plane: zx,
            turn: cw
        }
    );
    let m = mv(&mut r, "G19 G3 Y10 Z0 J5 K0");
    let yz = Plane {
        first: 1,
        second: 2,
    };
    assert_eq!(
        m.shape,
        Shape::ArcCenter {
            center: [5.0, 0.0],
            plane: yz,
            turn: ccw
        }
    );
    // a full circle: I J without axis words
    mv(&mut r, "G17 G0 X10 Y0 Z0");
    let m = mv(&mut r, "G2 I-10 F600");
    assert_eq!(
        (m.to, m.shape),
        (
            [10.0, 0.0, 0.0, 1.0],
            Shape::ArcCenter {
                center: [0.0, 0.0],
                plane: xy,
                turn: cw
            }
        )
    );
    // absolute centres with G90.1
    let m = mv(&mut r, "G90.1 G3 X-10 Y0 I0 J0");
    assert_eq!(
        m.shape,
        Shape::ArcCenter {
            center: [0.0, 0.0],
            plane: xy,
            turn: ccw
        }
    );
}

#[test]
fn bad_arcs_are_errors() {
    let mut r = reader().with_arc_tolerance(0.002);
    mv(&mut r, "G0 X10 Y0");
    r.read_line(b"F600").unwrap();
    // the end is 0.003 off the circle of radius 10: more than the tolerance
    assert_eq!(
        err(&mut r, "G3 X0 Y10.003 I-10"),
        (1, ErrorKind::ArcRadiusMismatch)
    );
    // within it the arc is taken
    mv(&mut r, "G3 X0 Y10.0015 I-10");
    mv(&mut r, "G0 X10 Y0");
    assert_eq!(err(&mut r, "G2 X0 Y10"), (1, ErrorKind::ArcWithoutCenter));
    assert_eq!(
        err(&mut r, "G2 X0 Y10 R10 I-10"),
        (1, ErrorKind::ArcWithoutCenter)
    );
    assert_eq!(
        err(&mut r, "G2 X10 Y0 R10"),
        (1, ErrorKind::ArcFullCircleWithRadius)
    );
    assert_eq!(
        err(&mut r, "G2 X50 Y0 R10"),
        (1, ErrorKind::ArcRadiusMismatch)
    );
    assert_eq!(
        err(&mut r, "G2 X10 Y0 I0 J0"),
        (1, ErrorKind::ArcRadiusMismatch)
    );
    // the state is as before the bad lines
    assert_eq!(r.position(), [10.0, 0.0, 0.0, 0.0]);
}

#[test]
fn cubic_beziers_g5() {
    let mut r = reader();
    let m = mv(&mut r, "G5 I5 J10 P-5 Q10 X20 Y0 E3 F600");
    let Shape::Bezier { c1, c2 } = m.shape else {
        panic!("{m:?}")
    };
    assert_eq!((c1, c2), ([5.0, 10.0, 0.0, 1.0], [15.0, 10.0, 0.0, 2.0]));
    // without I J: the last P Q mirrored
    let m = mv(&mut r, "G5 P-5 Q-10 X40 Y0");
    let Shape::Bezier { c1, .. } = m.shape else {
        panic!("{m:?}")
    };
    assert_eq!([c1[0], c1[1]], [25.0, -10.0]);
    assert_eq!(err(&mut r, "G5 X60 Y0 I1 J1"), (1, ErrorKind::BadCubic));
    mv(&mut r, "G1 X41");
    assert_eq!(err(&mut r, "G5 X60 Y0 P1 Q1"), (1, ErrorKind::BadCubic));
    assert_eq!(
        err(&mut r, "G18 G5 X60 I1 J1 P1 Q1"),
        (5, ErrorKind::BadCubic)
    );
}

#[test]
fn dwells_and_path_modes() {
    let mut r = reader();
    assert_eq!(r.read_line(b"G4 P0.5").unwrap().action, Action::Dwell(0.5));
    assert_eq!(err(&mut r, "G4"), (1, ErrorKind::BadDwell));
    assert_eq!(err(&mut r, "G4 P-1"), (1, ErrorKind::BadDwell));
    let b = r.read_line(b"G64 P0.05").unwrap();
    assert_eq!(b.path_mode, Some(PathMode::Blend(Some(0.05))));
    assert_eq!(
        r.read_line(b"G64").unwrap().path_mode,
        Some(PathMode::Blend(None))
    );
    assert_eq!(
        r.read_line(b"G61").unwrap().path_mode,
        Some(PathMode::ExactStop)
    );
    let b = r.read_line(b"G20 G64 P0.001").unwrap();
    assert_eq!(b.path_mode, Some(PathMode::Blend(Some(0.0254))));
}

#[test]
fn ignored_codes_are_counted() {
    let mut r = reader();
    for line in ["M3 S12000", "T1 M6", "G28", "G54 G40 G49", "M3", "H1 D2"] {
        assert_eq!(
            r.read_line(line.as_bytes()).unwrap().action,
            Action::None,
            "{line}"
        );
    }
    let got: Vec<(String, u32)> = r
        .ignored()
        .kinds()
        .iter()
        .map(|(c, n)| (c.to_string(), *n))
        .collect();
    let want = [
        ("M3", 2),
        ("S", 1),
        ("T1", 1),
        ("M6", 1),
        ("G28", 1),
        ("G54", 1),
        ("G40", 1),
        ("G49", 1),
        ("H", 1),
        ("D", 1),
    ];
    assert_eq!(got, want.map(|(c, n)| (c.to_string(), n)));
    assert_eq!(
        Code {
            letter: b'G',
            tenths: 611
        }
        .to_string(),
        "G61.1"
    );
}

#[test]
fn comments_line_numbers_and_checksums() {
    let mut r = reader();
    let m = mv(&mut r, "N10 G1 (move) X1 F60 ; to x = 1");
    assert_eq!(m.to[0], 1.0);
    let body = "N11 G1 X2";
    let sum = body.bytes().fold(0_u8, |x, b| x ^ b);
    assert_eq!(mv(&mut r, &format!("{body}*{sum}")).to[0], 2.0);
    assert_eq!(
        err(&mut r, &format!("{body}*{}", sum ^ 7)),
        (10, ErrorKind::BadChecksum)
    );
    assert_eq!(
        r.read_line(b"(only a comment)").unwrap().action,
        Action::None
    );
    assert_eq!(r.read_line(b"").unwrap().action, Action::None);
}

#[test]
fn one_test_per_error() {
    let mut r = reader();
    assert_eq!(err(&mut r, "X1"), (1, ErrorKind::NoMotionMode));
    assert_eq!(err(&mut r, "G1 X1"), (1, ErrorKind::NoFeed));
    assert_eq!(err(&mut r, "G1 X1 F0"), (7, ErrorKind::NoFeed));
    assert_eq!(err(&mut r, "G0 A1"), (4, ErrorKind::UnknownAxis));
    assert_eq!(err(&mut r, "G0 G1 X1"), (4, ErrorKind::Repeated));
    assert_eq!(err(&mut r, "G0 X1 X2"), (7, ErrorKind::Repeated));
    assert_eq!(err(&mut r, "G0 X1.2.3"), (4, ErrorKind::BadNumber));
    assert_eq!(err(&mut r, "G0 X"), (4, ErrorKind::MissingValue));
    assert_eq!(err(&mut r, "G0 X#5"), (4, ErrorKind::MissingValue));
    assert_eq!(err(&mut r, "G0 [X1]"), (4, ErrorKind::Unexpected));
    assert_eq!(err(&mut r, "G0 (X1"), (4, ErrorKind::UnclosedComment));
    assert_eq!(err(&mut r, "G1.55 X1"), (1, ErrorKind::BadNumber));
    let e = r.read_line(b"G0 X-").unwrap_err();
    assert_eq!(
        (e.line, e.to_string()),
        (
            13,
            "line 13, column 4: a number that does not parse".to_string()
        )
    );
    assert_eq!(r.position(), [0.0; 4]);
    assert_eq!(
        Reader::new(*b"XQ").unwrap_err(),
        GcodeError {
            line: 0,
            column: 2,
            kind: ErrorKind::UnknownAxis
        }
    );
}

#[test]
fn a_program_from_a_serial_link_line_by_line() {
    let program = b"G21 G90\r\nG1 X10 F600\r\nG2 X20 Y0 R5\r\nG1 Y-5\r\n";
    let mut buffer = LineBuffer::<32>::new();
    let mut r = reader();
    let mut moves = 0;
    for &byte in program {
        if let Some(line) = buffer.push(byte)
            && let Action::Move(_) = r.read_line(line.unwrap()).unwrap().action
        {
            moves += 1;
        }
    }
    assert_eq!(
        (moves, r.lines(), r.position()),
        (3, 4, [20.0, -5.0, 0.0, 0.0])
    );
    assert_eq!(lines(program).count(), 4);
}

/// The moves read from a contour stream through the planner: its arcs are taken with the
/// reader's arc tolerance, and the motion ends at the program's end.
#[test]
fn the_moves_read_stream_through_the_planner() {
    let program = "G21 G90 G17\nG0 X0 Y0\nG1 X20 F3000\nG3 X30 Y10 I0 J10\nG1 Y20\nG2 X40 Y30 R10\nG5 I5 J0 P-5 Q0 X60 Y30\nG1 X60 Y0\n";
    let mut r = Reader::new(*b"XYZ").unwrap().with_arc_tolerance(0.002);
    let limits = Limits::new(200.0, 3000.0, 100_000.0).unwrap();
    let options = StreamOptions::new(1000.0)
        .with_tolerance(0.02)
        .with_arc_tolerance(0.002);
    let mut stream = Stream::<3, 32, 256>::new([0.0; 3], limits, options).unwrap();
    for line in lines(program.as_bytes()) {
        if let Action::Move(m) = r.read_line(line).unwrap().action {
            stream.push(&m).unwrap();
        }
    }
    stream.finish().unwrap();
    let mut pieces = strak_curves::heapless::Deque::<strak_trajectory::Piece<f64, 3>, 64>::new();
    while !stream.is_idle() {
        stream.poll(&mut pieces).unwrap();
        pieces.clear();
    }
    assert_eq!(stream.position().unwrap(), [60.0, 0.0, 0.0]);
    assert_eq!(stream.stats().moves, 6); // G0 X0 Y0 from the origin moves nothing
}

/// A program with a dwell and path-mode changes, executed on a stream: the motion rests at
/// the dwell's point for its 0.3 s (300 ticks at 1 kHz), the corners after `G64 P0.05` are
/// blended and those under `G61` stop, and it ends at the program's end.
#[test]
fn dwells_and_path_modes_drive_the_stream() {
    use strak_trajectory::{AxisState, Piece};
    let program =
        "G21 G90 G61\nG1 X10 F3000\nG1 X20 Y1\nG4 P0.3\nG64 P0.05\nG1 X30 Y0\nG1 X40 Y1\n";
    let mut r = Reader::new(*b"XY").unwrap();
    let limits = Limits::new(200.0, 3000.0, 100_000.0).unwrap();
    let options = StreamOptions::new(1000.0).with_faster_stops(false);
    let mut stream = Stream::<2, 16, 128>::new([0.0; 2], limits, options).unwrap();
    for line in lines(program.as_bytes()) {
        let block = r.read_line(line).unwrap();
        match block.path_mode {
            Some(PathMode::ExactStop) => stream.set_tolerance(0.0).unwrap(),
            Some(PathMode::Blend(p)) => stream.set_tolerance(p.unwrap_or(0.02)).unwrap(),
            None => {}
        }
        match block.action {
            Action::Move(m) => stream.push(&m).unwrap(),
            Action::Dwell(s) => stream.dwell(s).unwrap(),
            Action::None => {}
        }
    }
    stream.finish().unwrap();
    let mut queue = strak_curves::heapless::Deque::<Piece<f64, 2>, 64>::new();
    let mut x: Vec<[f64; 2]> = Vec::new();
    while !stream.is_idle() {
        stream.poll(&mut queue).unwrap();
        while let Some(p) = queue.pop_front() {
            let mut s = *p.axes();
            for _ in 0..p.ticks() {
                x.push(s.map(|a| a.position));
                s.iter_mut().for_each(AxisState::step);
            }
        }
    }
    let at_dwell = x.iter().filter(|p| **p == [20.0, 1.0]).count();
    assert!(
        (300..310).contains(&at_dwell),
        "{at_dwell} ticks at the dwell's point"
    );
    let stats = stream.stats();
    assert_eq!((stats.stops, stats.blends), (1, 1), "{stats:?}"); // the dwell ends its move at rest too
    assert_eq!(stream.position().unwrap(), [40.0, 1.0]);
}

/// Bad input never panics: arbitrary bytes, and lines of random words (valid and not), are
/// read into a block or a typed error naming a column within the line.
#[test]
fn any_bytes_read_without_panicking() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let word = (
        proptest::sample::select(b"GXYZEIJKRPQFMTSN(;*#.- ".to_vec()),
        -1e4..1e4_f64,
        any::<bool>(),
    )
        .prop_map(|(letter, value, plain)| {
            let mut w = vec![letter];
            if plain {
                w.extend(format!("{value:.3}").bytes());
            } else {
                w.extend(format!("{value}").bytes().take(3));
            }
            w
        });
    let line = proptest::collection::vec(word, 0..12).prop_map(|ws| ws.join(&b' '));
    let bytes = proptest::collection::vec(any::<u8>(), 0..64);
    let mut runner = TestRunner::new(Config {
        cases: 2_000,
        ..Config::default()
    });
    let r = std::cell::RefCell::new(reader());
    runner
        .run(&prop_oneof![line, bytes], |text| {
            match r.borrow_mut().read_line(&text) {
                Ok(_) => {}
                Err(e) => prop_assert!(
                    e.column >= 1 && e.column as usize <= text.len().max(1) + 1,
                    "{e:?} for {text:?}"
                ),
            }
            Ok(())
        })
        .unwrap();
}

/// A feeder holds one block: offering another while it holds one is refused and takes
/// nothing, and the held block goes on once the stream has room.
#[test]
fn a_feeder_holds_one_block() {
    use strak_gcode::Feeder;
    use strak_trajectory::Error;
    let limits = Limits::new(200.0, 3000.0, 100_000.0).unwrap();
    let mut stream = Stream::<2, 4, 16>::new([0.0; 2], limits, StreamOptions::new(1000.0)).unwrap();
    let mut r = Reader::new(*b"XY").unwrap();
    let mut feeder = Feeder::new(0.0);
    let mut offered = 0;
    for line in ["G1 X1 F600", "X2 Y1", "X3", "X4 Y0", "X5", "X6 Y1", "X7"] {
        let block = r.read_line(line.as_bytes()).unwrap();
        match feeder.offer(block, &mut stream) {
            Ok(()) => offered += 1,
            Err(e) => {
                assert_eq!(
                    e,
                    Error::CapacityExceeded {
                        capacity: 1,
                        required: 2
                    }
                );
                break;
            }
        }
    }
    assert!(!feeder.is_ready() && offered >= 2, "{offered}");
    let mut pieces = strak_curves::heapless::Deque::<strak_trajectory::Piece<f64, 2>, 64>::new();
    for _ in 0..10_000 {
        if feeder.retry(&mut stream).unwrap() {
            break;
        }
        stream.poll(&mut pieces).unwrap();
        pieces.clear();
    }
    assert!(feeder.is_ready());
}
