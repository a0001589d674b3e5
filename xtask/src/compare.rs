//! The firmware's output (defmt-print's text) parsed into streams, and each stream compared
//! with the host's samples bit for bit.
//!
//! The protocol is documented in `firmware-sim/qemu/src/lib.rs`:
//! `J job format source axes`, `S tick [bits, …]`, `E job format source samples`,
//! `C job format bytes pieces`, `DONE streams`.

use std::collections::BTreeMap;
use std::fmt;

use strak_trajectory::NumberFormat;

/// Identifies a stream: job name, playback format, source (`blob` | `device`).
pub(crate) type StreamKey = (String, NumberFormat, String);

/// One stream of samples from the firmware.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Stream {
    /// Number of axes.
    pub(crate) axes: usize,
    /// Every sample's bits, `3 · axes` per tick.
    pub(crate) bits: Vec<u64>,
    /// The sample count of the `E` line (`None`: the stream never ended).
    pub(crate) ended: Option<u32>,
}

/// What one firmware run printed.
#[derive(Clone, Debug, Default)]
pub(crate) struct FirmwareOutput {
    /// The streams, in the order they started.
    pub(crate) streams: Vec<(StreamKey, Stream)>,
    /// The device-compiled paths: (job, format) → (bytes, pieces).
    pub(crate) compiled: BTreeMap<(String, NumberFormat), (usize, usize)>,
    /// The stream count of the `DONE` line.
    pub(crate) done: Option<u32>,
    /// Lines that are not part of the protocol (errors, panics).
    pub(crate) other: Vec<String>,
}

impl FirmwareOutput {
    /// The stream `key`.
    pub(crate) fn stream(&self, key: &StreamKey) -> Option<&Stream> {
        self.streams.iter().find(|(k, _)| k == key).map(|(_, s)| s)
    }
}

fn words(line: &str) -> Vec<&str> {
    line.split_whitespace().collect()
}

/// Parses defmt-print's output (one log line per line; anything before the first protocol
/// word of a line is ignored, so a log-format prefix does not matter).
///
/// # Errors
/// A line of the protocol that does not parse (names the line), or samples outside a stream.
pub(crate) fn parse(text: &str) -> Result<FirmwareOutput, String> {
    let mut out = FirmwareOutput::default();
    let mut current: Option<usize> = None;
    for (n, raw) in text.lines().enumerate() {
        let line = raw.trim();
        let bad = || format!("firmware output line {}: cannot parse `{raw}`", n + 1);
        let w = words(line);
        let format = |i: usize| w.get(i).and_then(|f| f.parse::<NumberFormat>().ok());
        match w.first().copied() {
            Some("S") => {
                let i = current.ok_or_else(|| format!("{}: a sample outside a stream", bad()))?;
                let (_, stream) = &mut out.streams[i];
                let tick: usize = w.get(1).and_then(|t| t.parse().ok()).ok_or_else(bad)?;
                let list = line
                    .split_once('[')
                    .and_then(|(_, rest)| rest.strip_suffix(']'))
                    .ok_or_else(bad)?;
                let values: Vec<u64> = list
                    .split(',')
                    .map(|v| v.trim().parse::<u64>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| bad())?;
                let per = 3 * stream.axes;
                if values.len() != per || tick * per != stream.bits.len() {
                    return Err(format!(
                        "{}: expected tick {} with {per} values",
                        bad(),
                        stream.bits.len() / per.max(1)
                    ));
                }
                stream.bits.extend(values);
            }
            Some("J") if w.len() == 5 => {
                let axes: usize = w[4].parse().map_err(|_| bad())?;
                let key = (w[1].to_owned(), format(2).ok_or_else(bad)?, w[3].to_owned());
                if out.stream(&key).is_some() {
                    return Err(format!("{}: the stream started twice", bad()));
                }
                out.streams.push((
                    key,
                    Stream {
                        axes,
                        ..Stream::default()
                    },
                ));
                current = Some(out.streams.len() - 1);
            }
            Some("E") if w.len() == 5 => {
                let i = current.ok_or_else(bad)?;
                let key = (w[1].to_owned(), format(2).ok_or_else(bad)?, w[3].to_owned());
                if out.streams[i].0 != key {
                    return Err(format!("{}: ends another stream", bad()));
                }
                out.streams[i].1.ended = Some(w[4].parse().map_err(|_| bad())?);
                current = None;
            }
            Some("C") if w.len() == 5 => {
                let bytes = w[3].parse().map_err(|_| bad())?;
                let pieces = w[4].parse().map_err(|_| bad())?;
                let key = (w[1].to_owned(), format(2).ok_or_else(bad)?);
                out.compiled.insert(key, (bytes, pieces));
            }
            Some("DONE") if w.len() == 2 => {
                out.done = Some(w[1].parse().map_err(|_| bad())?);
            }
            None => {}
            _ => out.other.push(raw.to_owned()),
        }
    }
    Ok(out)
}

/// The first difference between a host stream and the firmware's.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Mismatch {
    /// The first tick whose sample differs (or that only one side has).
    pub(crate) tick: usize,
    /// Which value of the sample: `position x`, `velocity y`, … (`sample` when one side has
    /// no sample at this tick).
    pub(crate) value: String,
    /// The host's bits (`None`: the host has no sample at this tick).
    pub(crate) host: Option<u64>,
    /// The firmware's bits (`None`: the firmware has no sample at this tick).
    pub(crate) firmware: Option<u64>,
    /// The number format, for showing the bits as numbers.
    pub(crate) format: NumberFormat,
}

/// The bits of a sample value as the number they encode, for messages (`Q40` playback
/// samples in `I32F32`).
pub(crate) fn show_bits(format: NumberFormat, bits: u64) -> String {
    match format {
        #[allow(clippy::cast_possible_truncation)]
        NumberFormat::F32 => format!("{:?} ({bits:#010x})", f32::from_bits(bits as u32)),
        NumberFormat::F64 => format!("{:?} ({bits:#018x})", f64::from_bits(bits)),
        NumberFormat::Q40 => {
            let v = bits.cast_signed() as f64 / 4_294_967_296.0;
            format!("{v:?} ({bits:#018x})")
        }
    }
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let side = |b: Option<u64>| {
            b.map_or_else(|| "no sample".to_owned(), |b| show_bits(self.format, b))
        };
        write!(
            f,
            "first difference at tick {}, {}: host {}, firmware {}",
            self.tick,
            self.value,
            side(self.host),
            side(self.firmware)
        )
    }
}

const AXES: [&str; 4] = ["x", "y", "z", "w"];
const QUANTITIES: [&str; 3] = ["position", "velocity", "acceleration"];

/// Compares the host's bits with the firmware's, tick by tick; `Ok(samples)` when equal.
///
/// # Errors
/// The first differing tick and value.
pub(crate) fn compare(
    host: &[u64],
    firmware: &[u64],
    axes: usize,
    format: NumberFormat,
) -> Result<usize, Mismatch> {
    let per = 3 * axes.max(1);
    let ticks = host.len().max(firmware.len()).div_ceil(per);
    for tick in 0..ticks {
        let h = host.get(tick * per..(tick + 1) * per);
        let w = firmware.get(tick * per..(tick + 1) * per);
        let (h, w) = match (h, w) {
            (Some(h), Some(w)) => (h, w),
            (h, w) => {
                return Err(Mismatch {
                    tick,
                    value: "sample".to_owned(),
                    host: h.map(|h| h[0]),
                    firmware: w.map(|w| w[0]),
                    format,
                });
            }
        };
        if let Some(i) = h.iter().zip(w).position(|(a, b)| a != b) {
            return Err(Mismatch {
                tick,
                value: format!(
                    "{} {}",
                    QUANTITIES[i / axes],
                    AXES.get(i % axes).copied().unwrap_or("?")
                ),
                host: Some(h[i]),
                firmware: Some(w[i]),
                format,
            });
        }
    }
    Ok(ticks)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn output(bits: &[[u64; 6]]) -> String {
        let mut s = String::from("J job Q40 blob 2\n");
        for (i, b) in bits.iter().enumerate() {
            let list: Vec<String> = b.iter().map(u64::to_string).collect();
            s += &format!("S {i} [{}]\n", list.join(", "));
        }
        s += &format!("E job Q40 blob {}\nC job Q40 120 3\nDONE 1\n", bits.len());
        s
    }

    fn stream(bits: &[[u64; 6]]) -> Vec<u64> {
        bits.iter().flatten().copied().collect()
    }

    #[test]
    fn parses_the_protocol() {
        let host = [[1, 2, 3, 4, 5, 6], [7, 8, 9, 10, 11, u64::MAX]];
        let out = parse(&output(&host)).unwrap();
        let key = ("job".to_owned(), NumberFormat::Q40, "blob".to_owned());
        let s = out.stream(&key).unwrap();
        assert_eq!((s.axes, s.ended), (2, Some(2)));
        assert_eq!(s.bits, stream(&host));
        assert_eq!(out.done, Some(1));
        assert_eq!(
            out.compiled[&("job".to_owned(), NumberFormat::Q40)],
            (120, 3)
        );
        assert!(out.other.is_empty());
    }

    #[test]
    fn a_perturbed_host_stream_names_the_first_differing_tick_and_value() {
        let mut host: Vec<[u64; 6]> = (0..50)
            .map(|i| [i, i + 1, i + 2, i + 3, i + 4, i + 5])
            .collect();
        let firmware = parse(&output(&host)).unwrap();
        let key = ("job".to_owned(), NumberFormat::Q40, "blob".to_owned());
        let fw = &firmware.stream(&key).unwrap().bits;
        assert_eq!(compare(&stream(&host), fw, 2, NumberFormat::Q40), Ok(50));
        // corrupt the host's velocity y at tick 37 and the position x at tick 40
        host[37][3] ^= 1;
        host[40][0] ^= 1 << 40;
        let m = compare(&stream(&host), fw, 2, NumberFormat::Q40).unwrap_err();
        assert_eq!(m.tick, 37);
        assert_eq!(m.value, "velocity y");
        assert_eq!((m.host, m.firmware), (Some(40 ^ 1), Some(40)));
        let text = m.to_string();
        assert!(text.contains("tick 37"), "{text}");
        assert!(text.contains("velocity y"), "{text}");
    }

    #[test]
    fn a_short_stream_names_the_first_missing_tick() {
        let host: Vec<[u64; 6]> = (0..10).map(|i| [i; 6]).collect();
        let fw = stream(&host[..7]);
        let m = compare(&stream(&host), &fw, 2, NumberFormat::F32).unwrap_err();
        assert_eq!((m.tick, m.value.as_str()), (7, "sample"));
        assert_eq!((m.host, m.firmware), (Some(7), None));
        assert!(m.to_string().contains("firmware no sample"));
    }

    #[test]
    fn bits_show_as_numbers() {
        assert_eq!(
            show_bits(NumberFormat::F32, 0x3f80_0000),
            "1.0 (0x3f800000)"
        );
        assert_eq!(
            show_bits(NumberFormat::Q40, (-3_i64 << 31).cast_unsigned()),
            "-1.5 (0xfffffffe80000000)"
        );
    }

    #[test]
    fn malformed_lines_are_errors() {
        assert!(parse("S 0 [1, 2]\n").is_err()); // outside a stream
        assert!(parse("J a f32 blob 1\nS 0 [1, 2]\n").is_err()); // 2 values, 3 expected
        assert!(parse("J a f32 blob 1\nS 1 [1, 2, 3]\n").is_err()); // tick 1 before tick 0
        assert!(parse("J a fixed blob 1\n").is_err()); // not a format's name
        let out = parse("ERROR panic: boom\n").unwrap();
        assert_eq!(out.other, ["ERROR panic: boom"]);
    }
}
