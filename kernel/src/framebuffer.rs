//! The 320x200 frame presented in a firmware's framebuffer, where the card
//! cannot be put in mode 13h (a display controller with no VGA, or one the
//! kernel does not know how to take out of the UEFI firmware's mode): each
//! frame pixel becomes a `scale` x `scale` block, `scale` the largest whole
//! number that fits, the frame centred and black around it, every colour
//! the palette entry's 6-bit levels widened to 8 bits as QEMU's VGA shows
//! them (`scenes::palette::c6_to_8`), so a page looks the same both ways.

use alloc::vec;
use alloc::vec::Vec;

use bootloader_api::info::{FrameBuffer, PixelFormat};
use protocol::Presentation;
use raster::SCREEN;
use scenes::palette::{c6_to_8, ENTRIES};
use volatile::{VolatilePtr, VolatileRef};

use crate::serial;
use crate::vga::Palette;

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
    layout: Layout,
    bytes_per_pixel: usize,
    /// Bytes from one framebuffer row to the next.
    row_bytes: usize,
    presentation: Presentation,
    /// One frame row, scaled and encoded: written `scale` times.
    row: Vec<u8>,
}

impl Presenter {
    /// Takes `framebuffer` over, blacks it out and centres the frame in it.
    /// `None` if its pixel format is not RGB or BGR in 3 or 4 bytes, or it
    /// is smaller than the frame.
    pub fn new(framebuffer: FrameBuffer) -> Option<Self> {
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
        let pixels = VolatileRef::from_mut_ref(framebuffer.into_buffer()).into_ptr();
        pixels.fill(0);
        let row = vec![0; FRAME_WIDTH * scale * bytes_per_pixel];
        Some(Self { pixels, layout, bytes_per_pixel, row_bytes, presentation, row })
    }

    /// Where the frame goes, for `READY`.
    pub fn presentation(&self) -> Presentation {
        self.presentation
    }

    /// Puts `frame` (320x200 palette indices, row after row) on the screen
    /// in the colours of `palette`. Up to 4 MB of writes to a firmware's
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
