//! Firmware sizes read from the ELF section headers (no binutils needed), and the checked-in
//! expected sizes (`firmware-sim/qemu/sizes.txt`, as rtic keeps `.size` files).
//!
//! Like Berkeley `size`: `text` = allocated, non-writable sections (code, read-only data,
//! the vector table), `data` = allocated, writable sections with contents (their initial
//! values live in flash too), `bss` = allocated, writable sections without contents. Flash =
//! text + data.

use std::fmt;

use crate::budget;

/// Sizes in bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Sizes {
    /// Code and read-only data.
    pub(crate) text: u64,
    /// Initialized data.
    pub(crate) data: u64,
    /// Zero-initialized data.
    pub(crate) bss: u64,
}

impl Sizes {
    /// Flash: text + data.
    pub(crate) fn flash(&self) -> u64 {
        self.text + self.data
    }
}

impl fmt::Display for Sizes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "text {} data {} bss {} (flash {})",
            self.text,
            self.data,
            self.bss,
            self.flash()
        )
    }
}

const SHF_WRITE: u32 = 0x1;
const SHF_ALLOC: u32 = 0x2;
const SHT_NOBITS: u32 = 8;

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

/// The sizes of a little-endian ELF32 file (what the Cortex-M targets produce).
///
/// # Errors
/// Not an ELF32 little-endian file, or truncated section headers.
pub(crate) fn elf32_sizes(bytes: &[u8]) -> Result<Sizes, String> {
    if bytes.get(..4) != Some(b"\x7fELF".as_slice())
        || bytes.get(4) != Some(&1)
        || bytes.get(5) != Some(&1)
    {
        return Err("not a little-endian ELF32 file".to_owned());
    }
    let truncated = || "truncated ELF section headers".to_owned();
    let shoff = u32_at(bytes, 0x20).ok_or_else(truncated)? as usize;
    let shentsize = usize::from(u16_at(bytes, 0x2e).ok_or_else(truncated)?);
    let shnum = usize::from(u16_at(bytes, 0x30).ok_or_else(truncated)?);
    let mut sizes = Sizes::default();
    for i in 0..shnum {
        let h = shoff + i * shentsize;
        let kind = u32_at(bytes, h + 4).ok_or_else(truncated)?;
        let flags = u32_at(bytes, h + 8).ok_or_else(truncated)?;
        let size = u64::from(u32_at(bytes, h + 20).ok_or_else(truncated)?);
        if flags & SHF_ALLOC == 0 {
            continue;
        }
        if flags & SHF_WRITE == 0 {
            sizes.text += size;
        } else if kind == SHT_NOBITS {
            sizes.bss += size;
        } else {
            sizes.data += size;
        }
    }
    Ok(sizes)
}

/// One line of the expected-sizes file: firmware name, target, sizes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Expected {
    /// The binary's name.
    pub(crate) name: String,
    /// The target triple.
    pub(crate) target: String,
    /// The recorded sizes.
    pub(crate) sizes: Sizes,
}

/// The values of a line of the expected-sizes file.
const FIELDS: [&str; 3] = ["text", "data", "bss"];

/// The header of the expected-sizes file.
const HEADER: &str = "# Firmware sizes in bytes, read from the ELF section headers by `cargo xtask qemu`.\n\
     # xtask fails when a firmware's flash (text + data) grows more than 10 % over its line;\n\
     # `cargo xtask qemu --bless` rewrites this file.\n\
     # name target text data bss\n";

/// Parses the expected-sizes file: `name target text data bss` per line, `#` comments
/// (the format of [`crate::budget`]).
///
/// # Errors
/// The first line that does not parse, by its number.
pub(crate) fn parse_expected(text: &str) -> Result<Vec<Expected>, String> {
    let lines = budget::parse(text, FIELDS).map_err(|e| format!("the expected sizes: {e}"))?;
    Ok(lines
        .into_iter()
        .map(|b| {
            let [text, data, bss] = b.values;
            Expected {
                name: b.name,
                target: b.target,
                sizes: Sizes { text, data, bss },
            }
        })
        .collect())
}

/// The expected-sizes file for `entries` (the sizes as measured: the check allows
/// [`GROWTH`]).
pub(crate) fn write_expected(entries: &[Expected]) -> String {
    let lines: Vec<budget::Budget<3>> = entries
        .iter()
        .map(|e| budget::Budget {
            name: e.name.clone(),
            target: e.target.clone(),
            values: [e.sizes.text, e.sizes.data, e.sizes.bss],
        })
        .collect();
    budget::write(HEADER, &lines)
}

/// The allowed growth of flash over the expected size.
pub(crate) const GROWTH: f64 = 0.10;

/// Checks `actual` against `expected`: `Err` when flash grew more than [`GROWTH`].
///
/// # Errors
/// A message naming both sizes.
pub(crate) fn check(name: &str, expected: Sizes, actual: Sizes) -> Result<(), String> {
    let limit = expected.flash() as f64 * (1.0 + GROWTH);
    if actual.flash() as f64 > limit {
        Err(format!(
            "{name}: flash grew from {} to {} bytes (more than {:.0} %): find the cause, or accept \
             it with `cargo xtask qemu --bless` and commit firmware-sim/qemu/sizes.txt",
            expected.flash(),
            actual.flash(),
            GROWTH * 100.0
        ))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A minimal ELF32 with the given sections (type, flags, size).
    fn elf(sections: &[(u32, u32, u32)]) -> Vec<u8> {
        let mut b = vec![0_u8; 52];
        b[..6].copy_from_slice(b"\x7fELF\x01\x01");
        b[0x20..0x24].copy_from_slice(&52_u32.to_le_bytes());
        b[0x2e..0x30].copy_from_slice(&40_u16.to_le_bytes());
        b[0x30..0x32].copy_from_slice(&u16::try_from(sections.len()).unwrap().to_le_bytes());
        for (kind, flags, size) in sections {
            let mut h = vec![0_u8; 40];
            h[4..8].copy_from_slice(&kind.to_le_bytes());
            h[8..12].copy_from_slice(&flags.to_le_bytes());
            h[20..24].copy_from_slice(&size.to_le_bytes());
            b.extend(h);
        }
        b
    }

    #[test]
    fn sizes_follow_the_section_flags() {
        let b = elf(&[
            (1, SHF_ALLOC | 0x4, 1000),                // .text
            (1, SHF_ALLOC, 200),                       // .rodata
            (1, SHF_ALLOC | SHF_WRITE, 30),            // .data
            (SHT_NOBITS, SHF_ALLOC | SHF_WRITE, 4000), // .bss
            (1, 0, 99_999),                            // .defmt / debug info: not loaded
        ]);
        let s = elf32_sizes(&b).unwrap();
        assert_eq!(
            s,
            Sizes {
                text: 1200,
                data: 30,
                bss: 4000
            }
        );
        assert_eq!(s.flash(), 1230);
        assert!(elf32_sizes(b"not an elf").is_err());
        assert!(elf32_sizes(&b[..60]).is_err());
    }

    #[test]
    fn growth_beyond_ten_percent_fails() {
        let e = Sizes {
            text: 1000,
            data: 0,
            bss: 10,
        };
        assert!(check("fw", e, Sizes { text: 1100, ..e }).is_ok());
        let err = check("fw", e, Sizes { text: 1101, ..e }).unwrap_err();
        assert!(err.contains("1000 to 1101"), "{err}");
        assert!(check("fw", e, Sizes { text: 10, ..e }).is_ok());
    }

    #[test]
    fn expected_file_round_trips() {
        let entries = vec![Expected {
            name: "strak-qemu".to_owned(),
            target: "thumbv7m-none-eabi".to_owned(),
            sizes: Sizes {
                text: 1,
                data: 2,
                bss: 3,
            },
        }];
        assert_eq!(parse_expected(&write_expected(&entries)).unwrap(), entries);
        let e = parse_expected("# c\na b 1 2\n").unwrap_err();
        assert!(
            e.contains("line 2: expected `name target text data bss`"),
            "{e}"
        );
        assert!(parse_expected("a b 1 2 3\na b 1 2 3\n").is_err());
    }
}
