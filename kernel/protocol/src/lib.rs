//! The serial protocol between the kernel and the host, shared by both
//! sides so they cannot drift apart: every line and text either side
//! writes is written here, and read back here. `docs/protocol.md` is the
//! prose version of this crate.
//!
//! Host to kernel: one ASCII command per line (`\n`, a `\r` before it is
//! ignored), at most [`MAX_LINE`] bytes ([`Command`], in `commands`). Kernel
//! to host: frames, each a header line `@KIND LEN CRC32\n` (LEN in decimal,
//! CRC32 of the payload in 8 lowercase hex digits), then LEN payload bytes,
//! then `\n` ([`FrameHeader`], in `frames`); anything between frames is
//! noise and the host skips it. The texts the frames carry are in
//! `replies`, one file per reply ([`Ready`], [`Pong`], [`TscRate`],
//! [`ShowReply`], [`DrawReply`], [`BenchReply`], [`Listing`],
//! [`VgaCheck`], ...), and in `events` the frames that are sentences for
//! people, which the host reads back all the same: `ERR`
//! ([`ErrorReply`]), `LOG` ([`LogEvent`]) and `FATAL` ([`FatalReport`]). A host
//! on a line that can damage bytes seals its command lines (`#SEQ COMMAND
//! CRC32`, [`Sealed`], in `sealed`): the kernel refuses a damaged one and
//! echoes the sequence number in its reply's header.
#![no_std]

extern crate alloc;

mod commands;
mod events;
mod frames;
mod replies;
mod sealed;
mod upload;

pub use commands::{Command, CommandError, FaultKind, FIRST_INTERRUPT_VECTOR, STORM_VECTOR, STRAY_VECTOR};
pub use events::{
    EndedAt, ErrorReply, FatalReport, HpetRefusal, IoApicRefusal, LogEvent, MachineEvidence, MaskedAt, PageFaultCode,
    DOUBLE_FAULT_VECTOR, EXCEPTION_NAMES, PAGE_FAULT_VECTOR,
};
pub use frames::{FrameHeader, FrameKind};
pub use replies::{
    BenchReply, BenchRow, ChunkReply, Cleared, ClockReadings, ClockSource, DemoReply, DrawReply, Expected, Firmware,
    FramebufferCheck, HeapState, InterruptCounts, LineErrors, LineLosses, Listing, Machine, Malformed, MemoryType,
    Mismatch, PageMapping, PciAddress, PciId, Pong, Presentation, Raised, Ready, RegisterGroup, ShowReply, StrayRaised,
    TscRate, UploadReply, VgaCheck, Video, Window, BENCH_UNIT_LINE, OWN_METHOD, PONG,
};
pub use sealed::{unseal, Damaged, Sealed, SEAL_MARK};
pub use upload::{Receiving, Upload};

/// Longest command line the kernel accepts, terminator excluded.
pub const MAX_LINE: usize = 4096;
/// Seconds a command line may sit unfinished, no byte arriving, before the
/// kernel drops it (saying so in a `LOG` frame) and plays the show again:
/// far longer than any pause inside a line a program sends (a whole line
/// of [`MAX_LINE`] bytes takes 0.36 s at 115200 baud), and long enough
/// for a person typing at a terminal.
pub const PARTIAL_LINE_IDLE_SECONDS: u64 = 10;
/// Most kernel memory an uploaded scene may take: its packed bytes
/// (`UPLOAD`'s BYTES) and the scene they unpack to (its MEMORY,
/// `scenes::packed::memory`) together. 1 MiB of the kernel's 4 MiB heap:
/// a real outline of 100,000 vertices fits (about 300 KB packed, 800 KB
/// unpacked), and what is left holds the show's stage and what the
/// methods allocate to fill.
pub const UPLOAD_BUDGET: usize = 1 << 20;
/// Packed bytes the host puts in one `CHUNK`: 1,368 characters of base64
/// (the kernel takes any chunk that fits in [`MAX_LINE`]). On a line that
/// damages bytes a damaged chunk is sent again alone, and a shorter line is
/// damaged less often; at 115,200 baud the command and the kernel's answer
/// add about 3% to each chunk's time.
pub const CHUNK_BYTES: usize = 1024;
/// Bytes in a mode-13h framebuffer.
pub const FRAMEBUFFER_LEN: usize = 320 * 200;
/// Bytes in a dump: the 320x200 frame read back (from 0xA0000 on the VGA
/// path), then its 256 palette entries as 6-bit red, green, blue (read
/// back from the DAC on the VGA path).
pub const DUMP_LEN: usize = FRAMEBUFFER_LEN + 768;
/// The byte that starts every frame header.
pub const FRAME_MARK: u8 = b'@';

/// Draws per method a `BENCH` without REPEATS times.
pub const BENCH_DEFAULT_REPEATS: u8 = 3;
/// Most draws per method a `BENCH` may ask for: keeps one `BENCH` within a
/// few seconds of emulated time.
pub const BENCH_MAX_REPEATS: u8 = 31;
/// What `DEMO` takes for "every entry" where an entry is named.
pub const EVERY_ENTRY: &str = "*";

/// The exit code a host sends with `EXIT` to end a run cleanly.
pub const EXIT_SUCCESS: u8 = 0x10;
/// The exit code the kernel uses after a panic or CPU exception.
pub const EXIT_FAILURE: u8 = 0x11;

/// The process status QEMU's isa-debug-exit gives for kernel exit `code`:
/// `(code << 1) | 1`, so 0x10 gives 33 and 0x11 gives 35.
pub const fn qemu_status(code: u8) -> i32 {
    ((code as i32) << 1) | 1
}
