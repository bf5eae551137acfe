//! Added to bootloader's UEFI loader by the image build
//! (boot/image/src/bootloader.rs puts this file into the loader's source
//! as `src/polylab_verify.rs`, `sha256.rs` as `src/polylab_sha256.rs`, and
//! calls `check_kernel` and `check_config` where the loader reads those
//! files). Not part of the workspace: it is built for
//! x86_64-unknown-uefi with the loader's own dependencies.
//!
//! Under Secure Boot, shim checks this loader's signature, but the loader
//! reads `kernel-x86_64` and `boot.json` from the FAT with nothing checking
//! them: a signed loader would boot whatever kernel is put beside it. So
//! the image build writes the SHA-256 of the kernel and of `boot.json`
//! into [`DIGESTS`] before it signs the loader (the signature covers them),
//! and the loader refuses, on the screen and on COM1, any other file.
//!
//! It loads nothing else: a `ramdisk` on the volume (which bootloader's
//! loader would read and map for the kernel unchecked) is refused, and so
//! is an empty kernel, ramdisk or `boot.json` (whose zero-byte allocation
//! would otherwise stop the loader in a panic that names nothing).
//!
//! The image build reads the built loader before it signs it and refuses
//! one that lacks the words of any refusal ([`NOT_THE_KERNEL`] and the
//! others): each is in the loader only if the code that says it can run,
//! i.e. its check is called.
//!
//! The loader also carries the `.sbat` section shim 16 requires of every
//! image it starts (see [`SBAT`]).

use core::fmt::{self, Write};

use crate::polylab_sha256::sha256;

/// shim's SBAT data: its format's header line, then this component.
/// The generation (1) is what a revocation would raise.
const SBAT_CSV: &str = "sbat,1,SBAT Version,sbat,1,https://github.com/rhboot/shim/blob/main/SBAT.md\n\
                        polylab-loader,1,polylab,bootloader-x86_64-uefi,0.11.17,https://crates.io/crates/bootloader-x86_64-uefi\n";

/// The `.sbat` section. A section of its own by name (shim looks it up by
/// name), kept by `#[used]` though nothing reads it.
#[used]
#[unsafe(link_section = ".sbat")]
static SBAT: [u8; SBAT_CSV.len()] = bytes_of(SBAT_CSV.as_bytes());

/// The marker the image build finds (exactly once) in the built loader;
/// the 64 bytes after it are the kernel's SHA-256, then `boot.json`'s.
const MARKER: &[u8; 16] = b"polylab-digests:";
const DIGESTS_LEN: usize = MARKER.len() + 64;

/// The marker and two digests of zeros until the image build writes the
/// real ones in. Read volatile ([`expected`]): as far as the compiler
/// knows it is all zeros, and it must not fold that into the checks.
#[used]
static DIGESTS: [u8; DIGESTS_LEN] = placeholder();

const fn bytes_of<const N: usize>(bytes: &[u8]) -> [u8; N] {
    let mut array = [0; N];
    let mut i = 0;
    while i < N {
        array[i] = bytes[i];
        i += 1;
    }
    array
}

const fn placeholder() -> [u8; DIGESTS_LEN] {
    let mut array = [0; DIGESTS_LEN];
    let mut i = 0;
    while i < MARKER.len() {
        array[i] = MARKER[i];
        i += 1;
    }
    array
}

/// The digests the image build wrote in: (kernel, `boot.json`).
fn expected() -> ([u8; 32], [u8; 32]) {
    // SAFETY: `DIGESTS` is a static of plain bytes, valid and aligned for
    // the whole run; nothing writes it while the loader runs (the image
    // build wrote its bytes in the file).
    let digests = unsafe { core::ptr::read_volatile(&raw const DIGESTS) };
    let mut kernel = [0; 32];
    let mut config = [0; 32];
    kernel.copy_from_slice(&digests[MARKER.len()..MARKER.len() + 32]);
    config.copy_from_slice(&digests[MARKER.len() + 32..]);
    if kernel == [0; 32] || config == [0; 32] {
        refuse(format_args!(
            "this loader was built without the SHA-256 of its kernel and boot.json (the image build writes \
             them in before it signs the loader), so it boots nothing."
        ));
    }
    (kernel, config)
}

/// Words of each refusal that no other code in the loader says, one per
/// check (consts, not an array, so that each is in the built loader only
/// with the function that uses it); boot/image/src/secure_boot/loader.rs
/// requires each of them in the built loader.
const NOT_THE_KERNEL: &str = " is not the kernel this loader was signed for";
const NOT_THE_CONFIG: &str = " is not the boot.json this loader was signed for";
const EMPTY_FILE: &str = " is an empty file, which this loader never boots";
const RAMDISK_FOUND: &str = "a ramdisk is on the volume, and this loader loads none";

/// Returns if `kernel` is the kernel this loader was signed for; refuses
/// otherwise.
pub fn check_kernel(kernel: &[u8]) {
    let (found, expected) = (sha256(kernel), expected().0);
    if found != expected {
        refuse(format_args!(
            "kernel-x86_64{}: its SHA-256 is {}, the loader expects {}. {CHANGED}",
            NOT_THE_KERNEL,
            Hex(&found),
            Hex(&expected)
        ));
    }
}

/// Returns if `config` is the `boot.json` this loader was signed for;
/// refuses otherwise, and when there is none.
pub fn check_config(config: Option<&[u8]>) {
    let expected = expected().1;
    let Some(config) = config else {
        refuse(format_args!("boot.json is missing; this loader was signed for one with SHA-256 {}.", Hex(&expected)));
    };
    let found = sha256(config);
    if found != expected {
        refuse(format_args!(
            "boot.json{}: its SHA-256 is {}, the loader expects {}. {CHANGED}",
            NOT_THE_CONFIG,
            Hex(&found),
            Hex(&expected)
        ));
    }
}

/// Returns if the file `name` the loader is about to read has bytes;
/// refuses an empty one (bootloader's loader would ask the firmware for
/// a zero-page allocation and panic).
pub fn check_not_empty(name: &dyn fmt::Display, size: usize) {
    if size == 0 {
        refuse(format_args!("{name}{} (0 bytes). {CHANGED}", EMPTY_FILE));
    }
}

/// Returns if there was no `ramdisk` on the volume; refuses one: nothing
/// checks a ramdisk, and bootloader's loader would map it for the kernel.
pub fn check_no_ramdisk(found: bool) {
    if found {
        refuse(format_args!("{}: only kernel-x86_64 and boot.json are checked. {CHANGED}", RAMDISK_FOUND));
    }
}

/// What every refusal of a changed stick ends with.
const CHANGED: &str = "The stick was changed after `cargo xtask image` made it; write the image again.";

/// Says why on the screen (the firmware's console, which OVMF also copies
/// to its serial port) and on COM1, then stops the machine.
fn refuse(why: fmt::Arguments) -> ! {
    uefi::system::with_stdout(|screen| {
        let _ = screen.clear();
        let _ = writeln!(screen, "polylab: refusing to boot. {why}");
        let _ = writeln!(screen, "The machine stops here; switch it off.");
    });
    let _ = write!(Com1, "\npolylab: refusing to boot. {why}\nThe machine stops here; switch it off.\n");
    loop {
        x86_64::instructions::hlt();
    }
}

/// Bytes as lowercase hex.
struct Hex<'a>(&'a [u8]);

impl fmt::Display for Hex<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.iter().try_for_each(|byte| write!(f, "{byte:02x}"))
    }
}

/// COM1 as the firmware left it set up; each byte waits (a bounded
/// while) for the transmitter, so a PC without a UART (whose status port
/// reads 0xFF) only loses the text.
struct Com1;

impl Write for Com1 {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        use x86_64::instructions::port::Port;
        let mut data = Port::<u8>::new(0x3F8);
        let mut line_status = Port::<u8>::new(0x3FD);
        for byte in text.bytes() {
            for byte in if byte == b'\n' { &b"\r\n"[..] } else { core::slice::from_ref(&byte) } {
                for _ in 0..100_000 {
                    // SAFETY: reading COM1's line status register has no
                    // side effect.
                    if unsafe { line_status.read() } & 0x20 != 0 {
                        break;
                    }
                }
                // SAFETY: a byte to COM1's transmit register, the port a
                // PC's first serial port has; on a PC without one the
                // write goes nowhere.
                unsafe { data.write(*byte) };
            }
        }
        Ok(())
    }
}
