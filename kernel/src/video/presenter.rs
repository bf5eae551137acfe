//! The 320x200 frame presented in a firmware's framebuffer, where the card
//! cannot be put in mode 13h (a display controller with no VGA, or one the
//! kernel does not know how to take out of the UEFI firmware's mode): each
//! frame pixel becomes a `scale` x `scale` block, `scale` the largest whole
//! number that fits, the frame centred and black around it, every colour
//! the palette entry's 6-bit levels widened to 8 bits as QEMU's VGA shows
//! them (`scenes::palette::c6_to_8`), so a page looks the same both ways.
//!
//! The framebuffer is written through pages of the write-combining type
//! (`paging::set_memory_type`, `pat.rs`), as Linux maps such framebuffers
//! (`ioremap_wc`): the bootloader maps it write-back by the PAT, which
//! the firmware's MTRRs make uncacheable where the framebuffer is in the
//! PCI hole (each 8-byte store then its own bus transaction: 40 to 130 ms
//! for a 1080p frame) and leave write-back where it is not (a 64-bit BAR
//! above 4 GiB, where stores can sit in the cache and the screen shows
//! stale blocks). Write-combining gathers the stores into bursts, which
//! sit in the CPU's write-combining buffers in no promised order until
//! something drains them: each presentation ends with an SFENCE, so a
//! frame counts as shown only once all of it has left the CPU. The
//! framebuffer's alias in the bootloader's map of physical memory gets
//! the same type: the manual forbids a write-combining page aliased to a
//! cacheable one.

use alloc::vec;
use alloc::vec::Vec;

use bootloader_api::info::{FrameBuffer, PixelFormat};
use protocol::{FramebufferCheck, MemoryType, PageMapping, Presentation};
use raster::SCREEN;
use scenes::palette::{c6_to_8, Palette, ENTRIES};
use volatile::{VolatilePtr, VolatileRef};
use x86_64::{PhysAddr, VirtAddr};

use crate::platform::{paging, pat};
use crate::wire::serial;

/// Frame width and height in pixels.
const FRAME_WIDTH: usize = SCREEN.width as usize;
const FRAME_HEIGHT: usize = SCREEN.height as usize;

/// How one pixel's colour is laid out in the framebuffer's bytes: the two
/// formats bootloader's UEFI loader hands over (it refuses the others).
#[derive(Clone, Copy)]
enum Layout {
    /// Red, green, blue bytes in this order, then padding.
    Rgb,
    /// Blue, green, red, then padding (UEFI's usual 32-bit format).
    Bgr,
}

/// The firmware's framebuffer and where the frame goes in it.
pub struct Presenter {
    pixels: VolatilePtr<'static, [u8]>,
    /// Where the framebuffer starts, in the kernel's address space and in
    /// physical memory.
    start: VirtAddr,
    physical: PhysAddr,
    layout: Layout,
    bytes_per_pixel: usize,
    /// Bytes from one framebuffer row to the next.
    row_bytes: usize,
    presentation: Presentation,
    /// One frame row, scaled and encoded: written `scale` times.
    row: Vec<u8>,
}

impl Presenter {
    /// Takes `framebuffer` over (at physical address `physical`), maps it
    /// write-combining, blacks it out and centres the frame in it. `None`
    /// if its pixel format is not RGB or BGR in 3 or 4 bytes, or it is
    /// smaller than the frame.
    pub fn new(framebuffer: FrameBuffer, physical: PhysAddr) -> Option<Self> {
        let info = framebuffer.info();
        let layout = match info.pixel_format {
            PixelFormat::Rgb => Layout::Rgb,
            PixelFormat::Bgr => Layout::Bgr,
            _ => return None,
        };
        let bytes_per_pixel = info.bytes_per_pixel;
        // Three colour bytes, and at most one of padding, which `encode`
        // fills.
        let encodable = 3..=4;
        let scale = (info.width / FRAME_WIDTH).min(info.height / FRAME_HEIGHT);
        let row_bytes = info.stride.checked_mul(bytes_per_pixel)?;
        let last_byte = (info.height.checked_sub(1)?)
            .checked_mul(row_bytes)?
            .checked_add(info.width.checked_mul(bytes_per_pixel)?)?;
        if scale == 0 || !encodable.contains(&bytes_per_pixel) || info.stride < info.width || last_byte > info.byte_len
        {
            return None;
        }
        let presentation = Presentation {
            width: u32::try_from(info.width).ok()?,
            height: u32::try_from(info.height).ok()?,
            scale: u32::try_from(scale).ok()?,
            left: u32::try_from((info.width - FRAME_WIDTH * scale) / 2).ok()?,
            top: u32::try_from((info.height - FRAME_HEIGHT * scale) / 2).ok()?,
        };
        // Only the rows on the screen: a firmware may hand over its whole
        // aperture (hundreds of MB on a real GPU) as the framebuffer.
        let buffer = &mut framebuffer.into_buffer()[..last_byte];
        let (start, len) = (VirtAddr::from_ptr(buffer.as_ptr()), buffer.len() as u64);
        // Where a step fails (no RAM left for a page table), the pages keep
        // the type they had, and `mapping` reports what they have.
        let _ = paging::set_memory_type(start, len, MemoryType::WriteCombining);
        if let Some(alias) = paging::physical(physical.as_u64()) {
            let _ = paging::set_memory_type(alias, len, MemoryType::WriteCombining);
        }
        let pixels = VolatileRef::from_mut_ref(buffer).into_ptr();
        pixels.fill(0);
        pat::store_fence();
        let row = vec![0; FRAME_WIDTH * scale * bytes_per_pixel];
        Some(Self { pixels, start, physical, layout, bytes_per_pixel, row_bytes, presentation, row })
    }

    /// Where the frame goes, for `READY`.
    pub fn presentation(&self) -> Presentation {
        self.presentation
    }

    /// How the framebuffer is mapped, read back from the page tables.
    pub fn mapping(&self) -> Option<PageMapping> {
        paging::mapping(self.start, self.len())
    }

    /// Bytes of the framebuffer in use: the rows on the screen.
    fn len(&self) -> u64 {
        self.pixels.len() as u64
    }

    /// The `VGACHECK` answer: where the framebuffer is, how it is mapped
    /// (the kernel's mapping of it and its alias in the bootloader's map of
    /// physical memory, both of which [`Presenter::new`] made
    /// write-combining) and what a frame costs.
    pub fn check(&self) -> FramebufferCheck {
        let Presentation { width, height, scale, .. } = self.presentation;
        let alias = paging::physical(self.physical.as_u64()).and_then(|alias| paging::mapping(alias, self.len()));
        FramebufferCheck {
            width,
            height,
            scale,
            start: self.physical.as_u64(),
            end: self.physical.as_u64() + self.len() - 1,
            mapping: self.mapping(),
            alias,
            bytes_per_frame: (FRAME_WIDTH * FRAME_HEIGHT * (scale as usize).pow(2) * self.bytes_per_pixel) as u64,
            pat: pat::read(),
        }
    }

    /// Puts `frame` (320x200 palette indices, row after row) on the screen
    /// in the colours of `palette`, and drains the write-combining buffers
    /// ([`pat::store_fence`]). Up to 4 MB of writes to a firmware's
    /// framebuffer, so COM1 is polled after each row (`serial::poll`).
    pub fn show(&mut self, frame: VolatilePtr<'_, [u8]>, palette: &Palette) {
        let colors = self.encode(palette);
        let scale = self.presentation.scale as usize;
        let left = self.presentation.left as usize * self.bytes_per_pixel;
        let mut indices = [0; FRAME_WIDTH];
        for y in 0..FRAME_HEIGHT {
            frame.index(y * FRAME_WIDTH..(y + 1) * FRAME_WIDTH).copy_into_slice(&mut indices);
            let pixel_bytes = scale * self.bytes_per_pixel;
            for (block, &index) in self.row.chunks_exact_mut(pixel_bytes).zip(&indices) {
                for pixel in block.chunks_exact_mut(self.bytes_per_pixel) {
                    pixel.copy_from_slice(&colors[usize::from(index)][..self.bytes_per_pixel]);
                }
            }
            let first_row = self.presentation.top as usize + y * scale;
            for row in first_row..first_row + scale {
                let start = row * self.row_bytes + left;
                self.pixels.index(start..start + self.row.len()).copy_from_slice(&self.row);
            }
            serial::poll();
        }
        pat::store_fence();
    }

    /// The bytes of each palette entry in this framebuffer's layout (the
    /// first `bytes_per_pixel` of each are used, padding 0).
    fn encode(&self, palette: &Palette) -> [[u8; 4]; ENTRIES] {
        palette.map(|levels| {
            let [red, green, blue] = levels.map(c6_to_8);
            match self.layout {
                Layout::Rgb => [red, green, blue, 0],
                Layout::Bgr => [blue, green, red, 0],
            }
        })
    }
}
