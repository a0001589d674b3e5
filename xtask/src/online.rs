//! The online solves of the `icount` firmware, repeated on the host: the firmware prints,
//! per case, the sum of its moves' durations' bits (`O <case> <moves> <sum>`), and the host's
//! solver must give the same sum on the same moves (bit for bit: the solver does the same
//! IEEE operations in the same order on both).

#[path = "../../bench/src/online_cases.rs"]
#[allow(dead_code, unreachable_pub)]
mod cases;

use cases::{BENCH_SEED, OnlineCase, online_cases};
use strak_trajectory::{MoveOptions, OnlineMove, Real};

/// A line `O <case> <moves> <sum>` of the firmware's output.
#[derive(Debug, PartialEq)]
pub(crate) struct Solved {
    pub(crate) name: String,
    pub(crate) moves: usize,
    pub(crate) sum: u64,
}

/// The `O` lines of the firmware's decoded output.
///
/// # Errors
/// A line that does not parse.
pub(crate) fn parse(text: &str) -> Result<Vec<Solved>, String> {
    text.lines()
        .filter(|l| l.starts_with("O "))
        .map(
            |line| match line.split_whitespace().collect::<Vec<_>>()[..] {
                ["O", name, moves, sum] => Ok(Solved {
                    name: name.to_owned(),
                    moves: moves.parse().map_err(|_| format!("`{line}`: bad count"))?,
                    sum: sum.parse().map_err(|_| format!("`{line}`: bad sum"))?,
                }),
                _ => Err(format!("unexpected line `{line}`")),
            },
        )
        .collect()
}

/// The sum of the durations' bits of the first `moves` benchmark moves solved in `R`.
fn host_sum<R: Real>(
    moves: usize,
    narrow: impl Fn(&OnlineCase<f64, 3>) -> Option<OnlineCase<R, 3>>,
) -> Result<u64, String> {
    let options = MoveOptions::new();
    let mut sum = 0_u64;
    for (i, c) in online_cases::<3>(BENCH_SEED, false).take(moves).enumerate() {
        let c = narrow(&c).ok_or_else(|| format!("move {i} does not fit the format"))?;
        let m = OnlineMove::solve(&c.start, &c.target, &c.limits, &options)
            .map_err(|e| format!("move {i} does not solve on the host: {e}"))?;
        sum = sum.wrapping_add(m.duration().to_f64().to_bits());
    }
    Ok(sum)
}

/// Checks every `O` line against the host's solver.
///
/// # Errors
/// A case whose sum differs from the host's, or that names no known format.
pub(crate) fn check(solved: &[Solved]) -> Result<(), String> {
    for s in solved {
        let host = if s.name.contains("f32") {
            host_sum::<f32>(s.moves, OnlineCase::in_f32)?
        } else if s.name.contains("f64") {
            host_sum::<f64>(s.moves, |c| Some(*c))?
        } else {
            return Err(format!("{}: no format in the name", s.name));
        };
        if host != s.sum {
            return Err(format!(
                "{}: the device's {} solves differ from the host's (durations' bits summed: \
                 {} on the device, {host} on the host)",
                s.name, s.moves, s.sum
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sum_that_differs_from_the_host_fails() {
        let host = host_sum::<f64>(20, |c| Some(*c)).expect("solves");
        let text = format!("I x 1 1 1 1 0\nO online-f64-3axis 20 {host}\nDONE 1\n");
        let solved = parse(&text).expect("parses");
        assert_eq!(solved.len(), 1);
        assert!(check(&solved).is_ok());
        let wrong = [Solved {
            sum: host ^ 1,
            ..solved.into_iter().next().expect("one")
        }];
        assert!(check(&wrong).is_err());
        assert!(parse("O a b c").is_err());
    }
}
