//! The answer to `VGACHECK` (`OK` when it passes, `ERR` when not): every
//! mode-13h register and DAC entry read back, and how the kernel's page
//! tables map what the frame is written to; and a register that did not
//! read back as written, also sent alone in a `LOG` frame at boot.

use alloc::vec::Vec;
use core::fmt;

use super::fields::{Expected, Malformed};
use super::prose::Prose;
use super::ready::MemoryType;

/// A register group of the VGA, as a [`Mismatch`] names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RegisterGroup {
    Misc,
    Sequencer,
    Crtc,
    Graphics,
    Attribute,
    /// The index is the byte offset in the DAC: entry * 3 + component.
    Dac,
}

impl RegisterGroup {
    const ALL: [RegisterGroup; 6] = [
        RegisterGroup::Misc,
        RegisterGroup::Sequencer,
        RegisterGroup::Crtc,
        RegisterGroup::Graphics,
        RegisterGroup::Attribute,
        RegisterGroup::Dac,
    ];

    fn name(self) -> &'static str {
        match self {
            RegisterGroup::Misc => "misc",
            RegisterGroup::Sequencer => "sequencer",
            RegisterGroup::Crtc => "crtc",
            RegisterGroup::Graphics => "graphics",
            RegisterGroup::Attribute => "attribute",
            RegisterGroup::Dac => "dac",
        }
    }
}

/// The DAC's three components of an entry, in the order of its bytes.
const COMPONENTS: [&str; 3] = ["red", "green", "blue"];

/// A register that does not read back what mode 13h wrote:
/// `crtc[0x11]: expected 0x8e, read 0x0e`, `misc: ...`,
/// `dac[5].green: ...`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mismatch {
    pub group: RegisterGroup,
    /// The register's index in its group (0 for `Misc`).
    pub index: usize,
    pub expected: u8,
    pub actual: u8,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { group, index, expected, actual } = *self;
        match group {
            RegisterGroup::Misc => write!(f, "misc")?,
            RegisterGroup::Dac => write!(f, "dac[{}].{}", index / 3, COMPONENTS[index % 3])?,
            _ => write!(f, "{}[{index:#04x}]", group.name())?,
        }
        write!(f, ": expected {expected:#04x}, read {actual:#04x}")
    }
}

impl Mismatch {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("VGA mismatch", text);
        let mismatch = read_mismatch(&mut prose)?;
        prose.written_by(mismatch)
    }
}

fn read_mismatch(prose: &mut Prose<'_>) -> Result<Mismatch, Malformed> {
    let group = RegisterGroup::ALL
        .into_iter()
        .find(|group| prose.next_is(group.name()))
        .ok_or(prose.malformed(Expected::Shape("a VGA register group")))?;
    let index = match group {
        RegisterGroup::Misc => 0,
        RegisterGroup::Dac => {
            prose.expect("[", "`[`")?;
            let entry: usize = prose.number("DAC entry")?;
            prose.expect("].", "`].`")?;
            let component = COMPONENTS
                .iter()
                .position(|component| prose.next_is(component))
                .ok_or(prose.malformed(Expected::Value("DAC component")))?;
            // An entry no register index can name is refused, not wrapped.
            entry
                .checked_mul(3)
                .and_then(|first| first.checked_add(component))
                .ok_or(prose.malformed(Expected::Value("DAC entry")))?
        }
        _ => {
            prose.expect("[", "`[`")?;
            let index = prose.hex_of("register index")?;
            prose.expect("]", "`]`")?;
            index
        }
    };
    prose.expect(": expected ", "`: expected`")?;
    let expected = prose.hex_of("expected")?;
    prose.expect(", read ", "`, read`")?;
    let actual = prose.hex_of("read")?;
    Ok(Mismatch { group, index, expected, actual })
}

/// How a range of memory is mapped, as the kernel's page tables and the
/// PAT give it: `16 pages of 4 KiB, uncacheable (UC), PAT entry 3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PageMapping {
    /// The distinct pages the range lies in.
    pub pages: usize,
    /// The first page's size in bytes (4 KiB, 2 MiB or 1 GiB).
    pub page_size: u64,
    /// The PAT entry the first page selects, and the type it holds
    /// (`None`: an encoding the manual reserves).
    pub pat_entry: u8,
    pub memory: Option<MemoryType>,
    /// Whether every page is mapped as the first is.
    pub uniform: bool,
}

/// Bytes in a KiB and a MiB.
const KIB: u64 = 1 << 10;
const MIB: u64 = 1 << 20;

impl PageMapping {
    /// The memory type every page of the range has, if they agree on one.
    pub fn memory_type(&self) -> Option<MemoryType> {
        self.uniform.then_some(self.memory).flatten()
    }
}

impl fmt::Display for PageMapping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { pages, page_size, pat_entry, memory, uniform } = *self;
        write!(f, "{pages} page{}", if pages == 1 { "" } else { "s" })?;
        match page_size >= 2 * MIB {
            true => write!(f, " of {} MiB", page_size / MIB)?,
            false => write!(f, " of {} KiB", page_size / KIB)?,
        }
        match memory {
            Some(memory) => write!(f, ", {}, PAT entry {pat_entry}", memory.description())?,
            None => write!(f, ", a reserved type, PAT entry {pat_entry}")?,
        }
        if !uniform {
            write!(f, " (the first; the others differ)")?;
        }
        Ok(())
    }
}

fn read_mapping(prose: &mut Prose<'_>) -> Result<PageMapping, Malformed> {
    let pages = prose.number("pages")?;
    if !prose.next_is(" pages of ") {
        prose.expect(" page of ", "`page of`")?;
    }
    let size: u64 = prose.number("page size")?;
    let page_size = match prose.next_is(" MiB, ") {
        true => size * MIB,
        false => {
            prose.expect(" KiB, ", "`KiB` or `MiB`")?;
            size * KIB
        }
    };
    let memory = match prose.next_is("a reserved type") {
        true => None,
        false => Some(
            MemoryType::ALL
                .into_iter()
                .find(|memory| prose.next_is(memory.description()))
                .ok_or(prose.malformed(Expected::Value("memory type")))?,
        ),
    };
    prose.expect(", PAT entry ", "`PAT entry`")?;
    let pat_entry = prose.number("PAT entry")?;
    let uniform = !prose.next_is(" (the first; the others differ)");
    Ok(PageMapping { pages, page_size, pat_entry, memory, uniform })
}

/// `VGACHECK`'s answer on each path the frame can take (`kernel/src/video/screen.rs`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VgaCheck {
    /// Mode 13h: `vga: K mismatches[: M; M...]; window S-E: MAPPING; PAT
    /// 0x...` (or `window not mapped`): the registers and DAC entries
    /// that did not read back as written, how the VGA window is mapped,
    /// and the PAT MSR.
    Vga { mismatches: Vec<Mismatch>, window: Option<Window>, pat: u64 },
    /// The firmware's framebuffer: `vga: none in use, the frame is
    /// presented in the firmware's WxH framebuffer at scale S; framebuffer
    /// S-E: MAPPING; its alias in the physical-memory map: MAPPING; N
    /// bytes written a frame; PAT 0x...`: where the framebuffer is, how
    /// the kernel maps it and how its alias in the bootloader's map of all
    /// physical memory is mapped (either `not mapped`), and what a frame
    /// costs.
    Framebuffer(FramebufferCheck),
    /// No VGA and no framebuffer: nothing shows the frame.
    Nothing,
}

/// The VGA window and how it is mapped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Its first and last physical byte.
    pub start: u64,
    pub end: u64,
    pub mapping: PageMapping,
}

/// What `VGACHECK` says of the framebuffer path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FramebufferCheck {
    /// The framebuffer's size in pixels, and each frame pixel's side in it.
    pub width: u32,
    pub height: u32,
    pub scale: u32,
    /// Its first and last physical byte (of the rows on the screen).
    pub start: u64,
    pub end: u64,
    /// How the kernel's own mapping of it is mapped, and its alias in the
    /// map of all physical memory (`None`: not mapped).
    pub mapping: Option<PageMapping>,
    pub alias: Option<PageMapping>,
    /// Bytes written to present one frame.
    pub bytes_per_frame: u64,
    pub pat: u64,
}

impl VgaCheck {
    /// Whether the check passed (answered `OK`): on the VGA path every
    /// register read back, on the framebuffer path always; with nothing
    /// to show the frame, never.
    pub fn passed(&self) -> bool {
        match self {
            VgaCheck::Vga { mismatches, .. } => mismatches.is_empty(),
            VgaCheck::Framebuffer(_) => true,
            VgaCheck::Nothing => false,
        }
    }
}

/// `Some` mapping, or `not mapped`.
struct OrNotMapped(Option<PageMapping>);

impl fmt::Display for OrNotMapped {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(mapping) => write!(f, "{mapping}"),
            None => write!(f, "not mapped"),
        }
    }
}

const NOTHING: &str = "vga: none, and no framebuffer: nothing shows the frame";
const ALIAS: &str = "; its alias in the physical-memory map: ";

impl fmt::Display for VgaCheck {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VgaCheck::Vga { mismatches, window, pat } => {
                write!(f, "vga: {} mismatches", mismatches.len())?;
                for (i, mismatch) in mismatches.iter().enumerate() {
                    write!(f, "{}{mismatch}", if i == 0 { ": " } else { "; " })?;
                }
                match window {
                    Some(Window { start, end, mapping }) => write!(f, "; window {start:#x}-{end:#x}: {mapping}")?,
                    None => write!(f, "; window not mapped")?,
                }
                write!(f, "; PAT {pat:#018x}")
            }
            VgaCheck::Framebuffer(check) => {
                let FramebufferCheck { width, height, scale, start, end, mapping, alias, bytes_per_frame, pat } =
                    *check;
                write!(
                    f,
                    "vga: none in use, the frame is presented in the firmware's {width}x{height} framebuffer at \
                     scale {scale}; framebuffer {start:#x}-{end:#x}: {}{ALIAS}{}; {bytes_per_frame} bytes written a \
                     frame; PAT {pat:#018x}",
                    OrNotMapped(mapping),
                    OrNotMapped(alias)
                )
            }
            VgaCheck::Nothing => write!(f, "{NOTHING}"),
        }
    }
}

impl VgaCheck {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("VGACHECK", text);
        if prose.next_is(NOTHING) {
            return prose.written_by(VgaCheck::Nothing);
        }
        if prose.next_is("vga: none in use, the frame is presented in the firmware's ") {
            let width = prose.number("width")?;
            prose.expect("x", "`x`")?;
            let height = prose.number("height")?;
            prose.expect(" framebuffer at scale ", "`framebuffer at scale`")?;
            let scale = prose.number("scale")?;
            prose.expect("; framebuffer ", "`framebuffer`")?;
            let start = prose.hex("framebuffer start")?;
            prose.expect("-", "`-`")?;
            let end = prose.hex("framebuffer end")?;
            prose.expect(": ", "`: `")?;
            let mapping = read_or_not_mapped(&mut prose)?;
            prose.expect(ALIAS, "the alias's mapping")?;
            let alias = read_or_not_mapped(&mut prose)?;
            prose.expect("; ", "`; `")?;
            let bytes_per_frame = prose.number("bytes written a frame")?;
            prose.expect(" bytes written a frame; PAT ", "`bytes written a frame`")?;
            let pat = prose.hex("PAT")?;
            let check = FramebufferCheck { width, height, scale, start, end, mapping, alias, bytes_per_frame, pat };
            return prose.written_by(VgaCheck::Framebuffer(check));
        }
        prose.expect("vga: ", "`vga:`")?;
        let count: usize = prose.number("mismatches")?;
        prose.expect(" mismatches", "`mismatches`")?;
        let mut mismatches = Vec::new();
        for i in 0..count {
            prose.expect(if i == 0 { ": " } else { "; " }, "a mismatch")?;
            mismatches.push(read_mismatch(&mut prose)?);
        }
        let window = match prose.next_is("; window not mapped") {
            true => None,
            false => {
                prose.expect("; window ", "`window`")?;
                let start = prose.hex("window start")?;
                prose.expect("-", "`-`")?;
                let end = prose.hex("window end")?;
                prose.expect(": ", "`: `")?;
                Some(Window { start, end, mapping: read_mapping(&mut prose)? })
            }
        };
        prose.expect("; PAT ", "`PAT`")?;
        let pat = prose.hex("PAT")?;
        prose.written_by(VgaCheck::Vga { mismatches, window, pat })
    }
}

fn read_or_not_mapped(prose: &mut Prose<'_>) -> Result<Option<PageMapping>, Malformed> {
    match prose.next_is("not mapped") {
        true => Ok(None),
        false => read_mapping(prose).map(Some),
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;
    use std::vec;

    const UNCACHEABLE_4K: PageMapping =
        PageMapping { pages: 16, page_size: 4096, pat_entry: 3, memory: Some(MemoryType::Uncacheable), uniform: true };

    #[test]
    fn the_vga_paths_answer_round_trips_as_the_protocol_page_shows_it() {
        let window = Window { start: 0xa0000, end: 0xaffff, mapping: UNCACHEABLE_4K };
        let passed = VgaCheck::Vga { mismatches: vec![], window: Some(window), pat: 0x0007040600070406 };
        let text = passed.to_string();
        assert_eq!(
            text,
            "vga: 0 mismatches; window 0xa0000-0xaffff: 16 pages of 4 KiB, uncacheable (UC), PAT entry 3; \
             PAT 0x0007040600070406"
        );
        assert_eq!(VgaCheck::parse(&text), Ok(passed.clone()));
        let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/protocol.md"))
            .expect("docs/protocol.md is there");
        assert!(page.contains(&std::format!("`OK` `{text}`")), "docs/protocol.md's VGACHECK row lacks `OK` `{text}`");
        assert!(passed.passed());
        let mismatches = vec![
            Mismatch { group: RegisterGroup::Misc, index: 0, expected: 0x63, actual: 0x67 },
            Mismatch { group: RegisterGroup::Crtc, index: 0x11, expected: 0x8e, actual: 0x0e },
            Mismatch { group: RegisterGroup::Dac, index: 3 * 255 + 2, expected: 0, actual: 0x3f },
        ];
        let odd = PageMapping { pages: 1, page_size: 2 << 20, pat_entry: 7, memory: None, uniform: false };
        let failed = VgaCheck::Vga { mismatches, window: Some(Window { mapping: odd, ..window }), pat: 6 };
        let text = failed.to_string();
        assert!(text.contains("misc: expected 0x63, read 0x67; crtc[0x11]: expected 0x8e, read 0x0e; dac[255].blue:"));
        assert!(text.contains("1 page of 2 MiB, a reserved type, PAT entry 7 (the first; the others differ)"));
        assert_eq!(VgaCheck::parse(&text), Ok(failed.clone()));
        assert!(!failed.passed());
        let unmapped = VgaCheck::Vga { mismatches: vec![], window: None, pat: 0 };
        assert_eq!(VgaCheck::parse(&unmapped.to_string()), Ok(unmapped));
    }

    #[test]
    fn the_framebuffer_paths_answer_names_both_mappings_and_round_trips() {
        let wc = PageMapping {
            pages: 300,
            page_size: 4096,
            pat_entry: 1,
            memory: Some(MemoryType::WriteCombining),
            uniform: true,
        };
        let check = FramebufferCheck {
            width: 1280,
            height: 800,
            scale: 4,
            start: 0x8000_0000,
            end: 0x803e_7fff,
            mapping: Some(wc),
            alias: Some(PageMapping { page_size: 2 << 20, pages: 2, memory: Some(MemoryType::WriteBack), ..wc }),
            bytes_per_frame: 4_096_000,
            pat: 0x0007040600070106,
        };
        for check in [check, FramebufferCheck { alias: None, mapping: None, ..check }] {
            let answer = VgaCheck::Framebuffer(check);
            let text = answer.to_string();
            assert_eq!(VgaCheck::parse(&text), Ok(answer.clone()), "{text}");
            assert!(answer.passed());
        }
        assert!(VgaCheck::Framebuffer(check).to_string().contains(
            "framebuffer 0x80000000-0x803e7fff: 300 pages of 4 KiB, write-combining (WC), PAT entry 1; its alias in \
             the physical-memory map: 2 pages of 2 MiB, write-back (WB), PAT entry 1; 4096000 bytes written a frame"
        ));
        assert_eq!(VgaCheck::parse(NOTHING), Ok(VgaCheck::Nothing));
        assert!(!VgaCheck::Nothing.passed());
    }

    #[test]
    fn a_mismatch_round_trips_alone_and_garbage_is_refused() {
        let mismatch = Mismatch { group: RegisterGroup::Attribute, index: 0x10, expected: 0x41, actual: 0x01 };
        assert_eq!(mismatch.to_string(), "attribute[0x10]: expected 0x41, read 0x01");
        assert_eq!(Mismatch::parse(&mismatch.to_string()), Ok(mismatch));
        for garbage in [
            "attribute[0x10]: expected 0x41, read 0x1",
            "attribute[0x10]: expected 0x41, read 0x01; more",
            "palette[0x10]: expected 0x41, read 0x01",
            "misc[0x00]: expected 0x41, read 0x01",
            "dac[1].alpha: expected 0x41, read 0x01",
            "crtc[0x1]: expected 0x41, read 0x01",
            // Found by the `command` fuzz target: entry * 3 overflowed.
            "dac[10248191152060862009].green: expected 0x00, read 0x00",
            "dac[6148914691236517205].green: expected 0x00, read 0x00",
        ] {
            assert!(Mismatch::parse(garbage).is_err(), "{garbage}");
        }
        for garbage in [
            "vga: 1 mismatches; window not mapped; PAT 0x0000000000000000",
            "vga: 0 mismatches; window not mapped; PAT 0x0",
            "vga: 0 mismatches; window 0xa0000-0xaffff: 16 pages of 4 KiB, cached, PAT entry 3; PAT 0x0000000000000000",
            "vga: none",
        ] {
            assert!(VgaCheck::parse(garbage).is_err(), "{garbage}");
        }
    }
}
