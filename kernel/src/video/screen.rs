//! The screen: the 320x200 frame, one byte a pixel, row after row, and
//! the palette its bytes are shown in, on whichever path the machine
//! allows ([`Screen::open`]):
//! - mode 13h: the frame is video memory at physical 0xA0000 and the
//!   palette is in the DAC, both set by the kernel's own register writes;
//! - a firmware's framebuffer: the frame is the kernel's own memory, drawn
//!   exactly as video memory would be, and presented scaled in the
//!   framebuffer (`presenter.rs`) at the moments a VGA would show it;
//! - nothing: the frame is the kernel's own memory, shown nowhere.
//!
//! Drawing, the methods, the demo and the protocol are the same on every
//! path. What the methods draw into, the frame's memory as a span sink,
//! is `video/canvas.rs`'s [`Canvas`].

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;
use core::ptr::{self, NonNull};

use bootloader_api::BootInfo;
use protocol::{Firmware, LogEvent, MemoryType, Mismatch, VgaCheck, Video, Window, DUMP_LEN, FRAMEBUFFER_LEN};
use raster::{stores, MethodId};
use scenes::palette::{Palette, VGA_DEFAULT};
use scenes::{DrawReport, Scene};
use volatile::{VolatilePtr, VolatileRef};

use x86_64::VirtAddr;

use crate::platform::pci::{DisplayController, Displays};
use crate::platform::{paging, pat};
use crate::video::canvas::Canvas;
use crate::video::presenter::Presenter;
use crate::video::{card, vga};

/// Where the frame is shown.
enum Output {
    /// The card in mode 13h; the frame is its video memory. `cirrus`: a
    /// Cirrus GD5446, whose window is rewritten through the latches after
    /// each change of the picture, for QEMU to show all of it
    /// (`vga::rewrite_through_latches`).
    Vga { cirrus: bool },
    /// The frame presented in the firmware's framebuffer.
    Framebuffer(Presenter),
    /// Nowhere.
    Nothing,
}

/// The screen: the frame's canvas, where it is shown, and in what palette.
pub struct Screen {
    /// The frame's memory: 0xA0000 on the VGA path, the kernel's memory
    /// otherwise.
    canvas: Canvas,
    /// The palette the frame is shown in, set by [`Screen::use_palette`]:
    /// in the DAC on the VGA path.
    palette: Palette,
    output: Output,
    /// See [`Screen::display`] and [`Screen::findings`].
    display: Option<DisplayController>,
    findings: Vec<LogEvent>,
}

impl Screen {
    /// The screen on the best path the machine allows, cleared to black
    /// in the VGA default palette:
    /// - mode 13h where a VGA answers and is in a standard VGA mode: under
    ///   a BIOS, which leaves it in text mode, any VGA; under UEFI, a card
    ///   `card.rs` knows, once it has undone the firmware's mode, and only
    ///   where that VGA is the head the firmware used: the framebuffer the
    ///   firmware handed over is in its memory (or none was handed over);
    /// - else the firmware's framebuffer from the boot info, if there is
    ///   one the presenter can draw in (under UEFI; under a BIOS the boot
    ///   stages set no framebuffer mode);
    /// - else nothing.
    ///
    /// Panics on the VGA path if the bootloader did not map physical
    /// memory (main.rs's config asks for it): 0xA0000 would be out of
    /// reach.
    pub fn open(boot_info: &'static mut BootInfo, firmware: Firmware, displays: &Displays) -> Self {
        let framebuffer = match firmware {
            Firmware::Uefi => boot_info.framebuffer.take(),
            Firmware::Bios => None,
        };
        let physical = framebuffer
            .as_ref()
            .and_then(|framebuffer| paging::to_physical(VirtAddr::from_ptr(framebuffer.buffer().as_ptr())));
        let vga = displays.vga();
        let head = physical.and_then(|physical| displays.holding(physical.as_u64()));
        let mut findings = Vec::new();
        let vga_usable = match firmware {
            Firmware::Bios => vga::responds(),
            // Not a port of a card that is not the VGA, or is unknown, is
            // touched, the VGA's included; a card's own registers (the
            // Bochs interface's probe among them) only once the VGA has
            // answered at its standard ports.
            Firmware::Uefi => match vga.filter(DisplayController::is_the_vga) {
                Some(display) if physical.is_some() && head != Some(display) => {
                    findings.push(LogEvent::FramebufferBesideTheVga { vga_at: display.address });
                    false
                }
                Some(display) if vga::responds() => match card::identify(&display) {
                    Some(card) => {
                        card.undo_firmware_mode(&display);
                        true
                    }
                    None => false,
                },
                Some(_) | None => false,
            },
        };
        if firmware == Firmware::Uefi && framebuffer.is_none() {
            findings.push(LogEvent::NoFramebuffer);
        }
        let (mut screen, display) = if vga_usable {
            vga::set_mode_13h();
            let cirrus = vga.is_some_and(|display| card::is_cirrus(&display));
            (Self::on(vga_window(), Output::Vga { cirrus }), vga)
        } else {
            let presenter =
                framebuffer.zip(physical).and_then(|(framebuffer, physical)| Presenter::new(framebuffer, physical));
            let display = if presenter.is_some() { head.or(vga) } else { vga };
            let output = presenter.map_or(Output::Nothing, Output::Framebuffer);
            let frame = VolatileRef::from_mut_ref(Box::leak(vec![0; FRAMEBUFFER_LEN].into_boxed_slice())).into_ptr();
            (Self::on(frame, output), display)
        };
        screen.display = display;
        screen.findings = findings;
        // The text mode the BIOS left had other bytes in video memory.
        screen.clear(0);
        screen
    }

    /// A screen drawing into `pixels`, shown by `output`, with the VGA
    /// default palette loaded: the BIOS's text mode leaves the DAC set up
    /// for text.
    fn on(pixels: VolatilePtr<'static, [u8]>, output: Output) -> Self {
        if let Output::Vga { .. } = output {
            vga::load_dac(&VGA_DEFAULT);
        }
        Self { canvas: Canvas::new(pixels), palette: VGA_DEFAULT, output, display: None, findings: Vec::new() }
    }

    /// The display controller the frame goes to: on the framebuffer path
    /// the one whose memory holds the framebuffer, where one does; else
    /// the VGA (`pci::Displays::vga`).
    pub fn display(&self) -> Option<DisplayController> {
        self.display
    }

    /// What [`Screen::open`] found worth a `LOG` line before `READY`.
    pub fn findings(&self) -> &[LogEvent] {
        &self.findings
    }

    /// The memory type the output is written with, read back from the
    /// page tables and the PAT; `None` with no output (or pages that
    /// disagree).
    pub fn memory_type(&self) -> Option<MemoryType> {
        match &self.output {
            Output::Vga { .. } => paging::mapping(window_start(), WINDOW_LEN).and_then(|mapping| mapping.memory_type()),
            Output::Framebuffer(presenter) => presenter.mapping().and_then(|mapping| mapping.memory_type()),
            Output::Nothing => None,
        }
    }

    /// The path in use, for `READY`: on the VGA path with the count of
    /// registers and DAC entries that do not read back as written.
    pub fn video(&self) -> Video {
        match &self.output {
            Output::Vga { .. } => Video::Vga13h { mismatches: vga::verify(&self.palette).len() },
            Output::Framebuffer(presenter) => Video::Framebuffer(presenter.presentation()),
            Output::Nothing => Video::None,
        }
    }

    /// The `VGACHECK` answer for the path in use: on the VGA path every
    /// mode-13h register and DAC entry read back, and how the window is
    /// mapped (page size and memory type, read back from the page tables
    /// and the PAT); on the framebuffer path how the framebuffer is mapped
    /// (`framebuffer.rs`); with nothing to show the frame, that.
    pub fn check(&self) -> VgaCheck {
        match &self.output {
            Output::Vga { .. } => VgaCheck::Vga {
                mismatches: vga::verify(&self.palette),
                window: paging::mapping(window_start(), WINDOW_LEN).map(|mapping| Window {
                    start: WINDOW_PHYSICAL,
                    end: WINDOW_PHYSICAL + WINDOW_LEN - 1,
                    mapping,
                }),
                pat: pat::read(),
            },
            Output::Framebuffer(presenter) => VgaCheck::Framebuffer(presenter.check()),
            Output::Nothing => VgaCheck::Nothing,
        }
    }

    /// The `LOG` lines of [`Screen::check`] before `READY`: each register
    /// or DAC entry of the VGA path that did not read back as written.
    pub fn mismatches(&self) -> Vec<Mismatch> {
        match self.output {
            Output::Vga { .. } => vga::verify(&self.palette),
            Output::Framebuffer(_) | Output::Nothing => Vec::new(),
        }
    }

    /// Uses `palette` from now on: loads it into the DAC on the VGA path,
    /// unless it is already there.
    pub fn use_palette(&mut self, palette: &Palette) {
        if self.palette != *palette {
            if let Output::Vga { .. } = self.output {
                vga::load_dac(palette);
            }
            self.palette = *palette;
        }
    }

    /// Shows the frame as it is now where a VGA would be showing it
    /// already: presents it in the firmware's framebuffer; on a Cirrus
    /// card, rewrites the window through the latches so that QEMU redraws
    /// all of it; nothing to do on the other paths.
    pub fn present(&mut self) {
        match &mut self.output {
            Output::Vga { cirrus: true } => vga::rewrite_through_latches(self.canvas.pixels()),
            Output::Framebuffer(presenter) => presenter.show(self.canvas.pixels(), &self.palette),
            Output::Vga { cirrus: false } | Output::Nothing => {}
        }
    }

    /// Waits for the start of a vertical retrace on the VGA path (the
    /// moment to copy a whole frame in without tearing); the other paths
    /// have no retrace to wait for.
    pub fn wait_for_retrace(&self) {
        if let Output::Vga { .. } = self.output {
            vga::wait_for_retrace();
        }
    }

    /// The canvas the methods draw into, for a drawing that is not a
    /// scene's (a still page of the show and its labels).
    pub fn canvas(&mut self) -> &mut Canvas {
        &mut self.canvas
    }

    /// Fills the screen with `color` of the VGA default palette.
    pub fn clear(&mut self, color: u8) {
        self.use_palette(&VGA_DEFAULT);
        stores::clear(&mut self.canvas, color);
        self.present();
    }

    /// Draws `scene` with `method` in the scene's palette (the VGA default
    /// with the scene's own entries set over it) and says how it went. The
    /// canvas's type is known to the fill, so each span is stored by
    /// [`Canvas`]'s `fill` inline, with no call.
    pub fn draw(&mut self, scene: &Scene, method: MethodId) -> Drawn {
        self.use_palette(&scene.dac());
        let strays = self.canvas.stray_spans();
        let report = scene.draw(method, &mut self.canvas);
        self.present();
        Drawn { report, stray_spans: self.canvas.stray_spans().wrapping_sub(strays) }
    }

    /// Puts a whole frame on the screen with one volatile copy (a `memcpy`
    /// that may move many bytes per instruction): `frame` is 320x200 bytes,
    /// row after row; bytes past 64,000 are ignored, a shorter frame
    /// replaces only the top of the screen.
    pub fn blit(&mut self, frame: &[u8]) {
        self.canvas.copy_from(frame);
        self.present();
    }

    /// A `DUMP` payload: the 64,000 bytes of the frame read back (from
    /// video memory on the VGA path), then the 768 palette bytes (read back
    /// from the card's DAC on the VGA path; the palette the frame is
    /// presented in on the others).
    pub fn dump(&self) -> Vec<u8> {
        let mut dump = vec![0; DUMP_LEN];
        let (framebuffer, dac) = dump.split_at_mut(FRAMEBUFFER_LEN);
        self.canvas.copy_into(framebuffer);
        match self.output {
            Output::Vga { .. } => dac.copy_from_slice(&vga::read_dac()),
            Output::Framebuffer(_) | Output::Nothing => dac.copy_from_slice(self.palette.as_flattened()),
        }
        dump
    }
}

/// The VGA window the kernel maps: 0xA0000 to 0xAFFFF, the 64 KiB that
/// graphics modes with a 64 KiB window (Graphics register 6 = 05, mode
/// 13h's) use; the 64,000 bytes of the frame are its start.
const WINDOW_PHYSICAL: u64 = 0xA0000;
const WINDOW_LEN: u64 = 0x10000;

/// Where the physical-memory map puts the window.
fn window_start() -> VirtAddr {
    paging::physical(WINDOW_PHYSICAL).expect("the bootloader maps the first 4 GiB of physical memory")
}

/// The mode-13h window 0xA0000..0xAFA00 in 4 KiB uncacheable pages
/// (`paging::set_memory_type`), where the bootloader's map of physical
/// memory had it in one large write-back page.
///
/// Uncacheable, not the framebuffer's write-combining: the kernel reads
/// video memory back (`DUMP` reads what the card holds), and a VGA's
/// memory reads have side effects (each loads the card's latches), which
/// the speculative reads write-combining allows could trigger at any
/// time; the frame is small (64,000 bytes, an eighth of them 8-byte
/// stores, [`Screen::fill`]), so bursts would save little; and UC is the
/// type a PC's firmware gives this range itself.
fn vga_window() -> VolatilePtr<'static, [u8]> {
    let start = window_start();
    if let Err(error) = paging::set_memory_type(start, WINDOW_LEN, MemoryType::Uncacheable) {
        panic!("the VGA window could not be mapped uncacheable: {error}");
    }
    let pixels = usize::try_from(start.as_u64())
        .ok()
        .and_then(|start| NonNull::new(ptr::with_exposed_provenance_mut::<u8>(start)))
        .map(|start| NonNull::slice_from_raw_parts(start, FRAMEBUFFER_LEN))
        .expect("the VGA window's address fits and is not null");
    // SAFETY: the physical-memory map maps these 64,000 bytes to the VGA
    // window 0xA0000..0xAFA00 (uncacheable since the call above): device
    // memory, valid for volatile reads and writes for the whole run and
    // never a Rust object, so nothing else holds a reference into it.
    // `Screen::open` calls this once.
    unsafe { VolatilePtr::new(pixels) }
}

/// What [`Screen::draw`] did.
pub struct Drawn {
    pub report: DrawReport,
    /// Spans a method emitted outside the screen (a method bug), dropped.
    pub stray_spans: usize,
}
