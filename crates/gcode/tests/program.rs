//! A program handed to a stream as its moves arrive: the steps of `Program`, its errors
//! naming the line, and the end of the program.

use heapless::Deque;
use strak_gcode::{ErrorKind, FeedError, Program, Reader, Step, arrived};
use strak_trajectory::{Error, Limits, Piece, Stream, StreamOptions};

type Pieces = Deque<Piece<f64, 2>, 64>;

fn stream() -> Stream<2, 4, 16> {
    let limits = Limits::new(100.0, 1_000.0, 50_000.0).unwrap();
    Stream::new(
        [0.0; 2],
        limits,
        StreamOptions::new(1_000.0).with_tolerance(0.01),
    )
    .unwrap()
}

fn reader() -> Reader<2> {
    Reader::new(*b"XY").unwrap()
}

#[test]
fn lines_are_read_as_their_moves_arrive() {
    let text = b"G21 (mm)\nG1 X10 F600\nM3 S100\nG1 Y10\nG4 P0.1\nG1 X0\n";
    let mut s = stream();
    let mut p = Program::new(text, reader(), 0.01);
    // one move arrived: the comment line and the first move are read, the spindle line waits
    assert_eq!(p.step(&mut s, 1), Ok(Step::Handed { moved: false }));
    assert_eq!(p.step(&mut s, 1), Ok(Step::Handed { moved: true }));
    assert_eq!(p.step(&mut s, 1), Ok(Step::Waiting));
    assert_eq!((p.motions(), p.reader().lines()), (1, 2));
    // the dwell counts as an arrival
    assert_eq!(p.feed(&mut s, 3), Ok(Step::Waiting));
    assert_eq!((p.motions(), p.reader().lines()), (3, 5));
    let mut pieces = Pieces::new();
    let mut tick = 0;
    while !(p.is_finished() && s.is_idle()) {
        let step = p.feed(&mut s, usize::MAX).unwrap();
        assert!(matches!(step, Step::Finished | Step::Full), "{step:?}");
        s.poll(&mut pieces).unwrap();
        pieces.clear();
        tick += 1;
        assert!(tick < 100_000);
    }
    assert_eq!(p.feed(&mut s, usize::MAX), Ok(Step::Finished));
    assert_eq!((p.motions(), s.position().unwrap()), (4, [0.0, 10.0]));
}

#[test]
fn a_full_stream_holds_the_block_until_a_poll() {
    let mut text = String::from("G1 F6000\n");
    for i in 1..=40 {
        text += &format!("G1 X{} Y{}\n", i % 2, i);
    }
    let mut s = stream();
    let mut p = Program::new(text.as_bytes(), reader(), 0.01);
    assert_eq!(p.feed(&mut s, usize::MAX), Ok(Step::Full));
    let held = p.motions();
    assert!(held < 40, "{held}");
    // still full without a poll: nothing more is read
    assert_eq!(p.step(&mut s, usize::MAX), Ok(Step::Full));
    assert_eq!(p.motions(), held);
    let mut pieces = Pieces::new();
    let mut polls = 0;
    while p.feed(&mut s, usize::MAX) == Ok(Step::Full) {
        s.poll(&mut pieces).unwrap();
        pieces.clear();
        polls += 1;
        assert!(polls < 100_000);
    }
    assert_eq!(p.motions(), 40);
}

#[test]
fn errors_name_the_line() {
    let mut s = stream();
    let mut p = Program::new(b"G1 X1 F60\nG1 X\n", reader(), 0.01);
    match p.feed(&mut s, usize::MAX) {
        Err(FeedError::Line(e)) => {
            assert_eq!((e.line, e.kind), (2, ErrorKind::MissingValue));
        }
        other => panic!("{other:?}"),
    }
    // an arc the reader takes (its end 0.001 off the circle, within 0.002) but a stream of
    // arc tolerance 10⁻⁶ refuses: the reader and the stream are to be given one tolerance
    let mut s = stream();
    let text = b"G1 X10 F600\nG3 X0 Y10.001 I-10\n";
    let mut p = Program::new(text, reader().with_arc_tolerance(0.002), 0.01);
    match p.feed(&mut s, usize::MAX) {
        Err(FeedError::Refused { line, error }) => {
            assert_eq!(line, 2);
            assert!(matches!(error, Error::Curve(_)), "{error:?}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn arrivals_count_from_tick_zero() {
    assert_eq!(arrived(0, 1.0), 1);
    assert_eq!(arrived(9, 10.0), 1);
    assert_eq!(arrived(10, 10.0), 2);
    assert_eq!(arrived(u64::MAX, 0.5), usize::MAX);
}
