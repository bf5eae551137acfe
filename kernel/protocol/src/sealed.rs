//! Host to kernel, over a line that may damage bytes: the seal a host can
//! put on a command line, `#SEQ COMMAND CRC32`, so that a damaged line is
//! refused rather than run, and the reply can name the line it answers.
//!
//! `SEQ` is a sequence number the host chooses (decimal, `u32`) and the
//! kernel echoes in its reply's header ([`FrameHeader::seq`](crate::FrameHeader));
//! `CRC32` is the CRC-32 (the zlib polynomial, as for frames) of every
//! byte of the line before the space that precedes it, `#` included, in 8
//! lowercase hex digits. A line that starts with `#` must be a whole,
//! intact seal; any other line is a plain command, as a person types it.
//! Damage cannot turn one into the other unnoticed: a damaged `#` leaves a
//! first word that is no command, and damage anywhere else fails the CRC.

use core::fmt::{self, Write};

/// The byte a sealed line starts with.
pub const SEAL_MARK: u8 = b'#';

/// A command line with its seal: `Display` writes `#SEQ COMMAND CRC32`
/// (no terminator).
pub struct Sealed<'a, C: fmt::Display> {
    pub seq: u32,
    pub command: &'a C,
}

impl<C: fmt::Display> fmt::Display for Sealed<'_, C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut crc = Crc32Writer(crc32fast::Hasher::new());
        write!(crc, "#{} {}", self.seq, self.command)?;
        write!(f, "#{} {} {:08x}", self.seq, self.command, crc.0.finalize())
    }
}

/// A line that starts with [`SEAL_MARK`] but is not an intact seal: its
/// CRC does not check, or its sequence number or CRC is missing or
/// malformed. The kernel answers `ERR` with no sequence number (the one in
/// the line cannot be trusted) and runs nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Damaged;

impl fmt::Display for Damaged {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "damaged sealed line: its CRC-32 or sequence number does not check; nothing was run")
    }
}

/// A command line read: its sequence number if it was sealed, and the
/// command's bytes (the whole line if it was plain; a `\r` before the end
/// is dropped either way).
pub fn unseal(line: &[u8]) -> Result<(Option<u32>, &[u8]), Damaged> {
    let line = line.strip_suffix(b"\r").unwrap_or(line);
    if line.first() != Some(&SEAL_MARK) {
        return Ok((None, line));
    }
    let last_space = line.iter().rposition(|&b| b == b' ').ok_or(Damaged)?;
    let (covered, crc) = (&line[..last_space], &line[last_space + 1..]);
    if crc.len() != 8 || !crc.iter().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(b)) {
        return Err(Damaged);
    }
    let crc = core::str::from_utf8(crc).ok().and_then(|hex| u32::from_str_radix(hex, 16).ok()).ok_or(Damaged)?;
    if crc32fast::hash(covered) != crc {
        return Err(Damaged);
    }
    let rest = &covered[1..];
    let seq_end = rest.iter().position(|&b| b == b' ').ok_or(Damaged)?;
    let seq = &rest[..seq_end];
    if seq.is_empty() || !seq.iter().all(u8::is_ascii_digit) {
        return Err(Damaged);
    }
    let seq = core::str::from_utf8(seq).ok().and_then(|digits| digits.parse().ok()).ok_or(Damaged)?;
    Ok((Some(seq), &rest[seq_end + 1..]))
}

/// `fmt::Write` into a CRC-32: formats text into its checksum without
/// allocating it.
pub(crate) struct Crc32Writer(pub(crate) crc32fast::Hasher);

impl Write for Crc32Writer {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        self.0.update(text.as_bytes());
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::Command;
    use std::string::ToString;
    use std::vec::Vec;

    fn sealed(seq: u32, command: &Command) -> std::string::String {
        Sealed { seq, command }.to_string()
    }

    #[test]
    fn a_sealed_line_opens_to_its_sequence_number_and_command() {
        let command = Command::Draw { scene: "abrash38-1", method: Some(raster::MethodId::Exact) };
        let line = sealed(17, &command);
        let crc = crc32fast::hash(b"#17 DRAW abrash38-1 exact");
        assert_eq!(line, std::format!("#17 DRAW abrash38-1 exact {crc:08x}"));
        assert_eq!(unseal(line.as_bytes()), Ok((Some(17), &b"DRAW abrash38-1 exact"[..])));
        let with_cr = std::format!("{line}\r");
        assert_eq!(unseal(with_cr.as_bytes()), Ok((Some(17), &b"DRAW abrash38-1 exact"[..])));
    }

    #[test]
    fn a_plain_line_passes_through_as_typed() {
        assert_eq!(unseal(b"PING"), Ok((None, &b"PING"[..])));
        assert_eq!(unseal(b"CLEAR 7\r"), Ok((None, &b"CLEAR 7"[..])));
        assert_eq!(unseal(b""), Ok((None, &b""[..])));
    }

    /// Every single-bit flip, every dropped byte and every inserted byte
    /// (of a few values) of a sealed line is either refused as damaged or,
    /// where the `#` itself is hit, turns the line into a plain one whose
    /// first word is no command.
    #[test]
    fn no_single_fault_passes_for_a_command() {
        let line = sealed(4_000_000_000, &Command::Poly { method: raster::MethodId::Wgt, spec: "color=4 0,0 9,0 0,9" });
        let line = line.as_bytes();
        let mut damaged: Vec<Vec<u8>> = Vec::new();
        for i in 0..line.len() {
            for bit in 0..8 {
                let mut copy = line.to_vec();
                copy[i] ^= 1 << bit;
                damaged.push(copy);
            }
            let mut dropped = line.to_vec();
            dropped.remove(i);
            damaged.push(dropped);
            for byte in [b'#', b' ', b'0', b'a', 0xff] {
                let mut inserted = line.to_vec();
                inserted.insert(i, byte);
                damaged.push(inserted);
            }
        }
        for copy in damaged {
            match unseal(&copy) {
                Err(Damaged) => {}
                Ok((None, plain)) => {
                    assert!(Command::parse(plain).is_err(), "{:?} runs as a plain command", copy.escape_ascii());
                }
                Ok((Some(seq), command)) => {
                    panic!("{:?} opens to #{seq} {:?}", copy.escape_ascii().to_string(), command.escape_ascii())
                }
            }
        }
    }

    #[test]
    fn malformed_seals_are_damaged() {
        let good = sealed(3, &Command::Ping);
        let crc = &good[good.len() - 8..];
        for bad in [
            "#3 PING".to_string(),
            std::format!("#3 PING {}", crc.to_uppercase()),
            std::format!("#3 PING {crc}0"),
            std::format!("# PING {crc}"),
            std::format!("#x PING {crc}"),
            std::format!("#3PING {crc}"),
            "#".to_string(),
        ] {
            assert_eq!(unseal(bad.as_bytes()), Err(Damaged), "{bad}");
        }
        // A well-formed seal whose sequence number overflows is damaged too.
        let huge = "#4294967296 PING";
        let huge = std::format!("{huge} {:08x}", crc32fast::hash(huge.as_bytes()));
        assert_eq!(unseal(huge.as_bytes()), Err(Damaged));
    }
}
