//! Stores any sink may use: the store of one span into bytes
//! ([`set_bytes`]), of the first bytes of a 64-byte window ([`set_prefix`]),
//! and a whole target filled through a sink's spans
//! ([`clear`]). The sink interface itself, [`SpanSink`], is the target's
//! (`target.rs`).

use crate::target::SpanSink;

/// Fills the whole target with one colour through its span interface.
pub fn clear<S: SpanSink + ?Sized>(sink: &mut S, color: u8) {
    let size = sink.size();
    for y in 0..size.height {
        sink.span(y, 0, size.width, color);
    }
}

/// Sets every byte of `bytes` to `color`, as a span store: a span of up
/// to 64 bytes is two stores of its width class (1, 4, 8, 16 or 32 bytes;
/// the wide ones may be split into 16-byte stores on the baseline target),
/// overlapping in the middle, with no loop and no call. A longer one is,
/// where the build targets a CPU with AVX2 (`-C target-cpu=native` on a
/// recent x86-64, as `cargo xtask lab` builds), up to 512 bytes, two,
/// four or six blocks of 64 or 128 bytes, from both ends, overlapping in
/// the middle, with no loop and no call either; past 512 bytes, or on a
/// CPU without AVX2, one `memset`, whose library version picks the widest
/// stores the machine has. A `memset` call costs more than the whole store
/// on the short spans that most polygons are made of, and more than the
/// inline blocks on the holed polygons' spans of up to 180 bytes, while on
/// the large convex polygons' rows of up to 320 bytes the two were as
/// quick (docs/lab-history.md#2026-11-29-long-spans-inline-e3eca29); with 16-byte stores only, the call is the
/// cheaper. The blocks are written out, not looped over: the compiler
/// turns a loop of such stores into a `memset` call.
#[inline(always)]
pub fn set_bytes(bytes: &mut [u8], color: u8) {
    store_span::<{ cfg!(target_feature = "avx2") }>(bytes, color);
}

/// [`set_bytes`], storing spans of 65 to 512 bytes in inline blocks
/// where `BLOCKS`, else by a `memset`.
#[inline(always)]
fn store_span<const BLOCKS: bool>(bytes: &mut [u8], color: u8) {
    let n = bytes.len();
    if n <= 16 {
        if n >= 8 {
            bytes[..8].copy_from_slice(&[color; 8]);
            bytes[n - 8..].copy_from_slice(&[color; 8]);
        } else if n >= 4 {
            bytes[..4].copy_from_slice(&[color; 4]);
            bytes[n - 4..].copy_from_slice(&[color; 4]);
        } else if n > 0 {
            // Bytes 0, n / 2 and n - 1 cover one to three bytes.
            bytes[0] = color;
            bytes[n / 2] = color;
            bytes[n - 1] = color;
        }
    } else if n <= 32 {
        bytes[..16].copy_from_slice(&[color; 16]);
        bytes[n - 16..].copy_from_slice(&[color; 16]);
    } else if n <= 64 {
        bytes[..32].copy_from_slice(&[color; 32]);
        bytes[n - 32..].copy_from_slice(&[color; 32]);
    } else if BLOCKS && n <= 512 {
        // In the order of their addresses: the first 64 bytes, then as
        // the span needs them the next 64 and the 128 after those; the
        // same again, backwards from the last byte.
        bytes[..64].copy_from_slice(&[color; 64]);
        if n > 128 {
            bytes[64..128].copy_from_slice(&[color; 64]);
        }
        if n > 256 {
            bytes[128..256].copy_from_slice(&[color; 128]);
            bytes[n - 256..n - 128].copy_from_slice(&[color; 128]);
        }
        if n > 128 {
            bytes[n - 128..n - 64].copy_from_slice(&[color; 64]);
        }
        bytes[n - 64..].copy_from_slice(&[color; 64]);
    } else {
        bytes.fill(color);
    }
}

/// Sets the first `length` bytes of a 64-byte `window` to `color`, where
/// `length` is at most 64, and leaves the rest as they were: on a CPU with
/// AVX-512 (BW), one store of the 64 bytes under a mask of `length` ones,
/// whatever the length, with no branch on it. Elsewhere the compiler
/// stores byte by byte, so there a sink should use [`set_bytes`] instead.
#[inline(always)]
pub fn set_prefix(window: &mut [u8; 64], length: usize, color: u8) {
    for (at, byte) in window.iter_mut().enumerate() {
        if at < length {
            *byte = color;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every length of a window sets that many bytes and no more.
    #[test]
    fn set_prefix_sets_exactly_the_first_bytes() {
        for length in 0..=64 {
            let mut window = [3u8; 64];
            set_prefix(&mut window, length, 9);
            let mut expected = [3u8; 64];
            expected[..length].fill(9);
            assert_eq!(window, expected, "length {length}");
        }
    }

    /// Every length up to 600 at every offset below 24, with the inline
    /// blocks and without them, against a plain slice fill: the
    /// overlapping stores set exactly the span.
    #[test]
    fn set_bytes_sets_exactly_the_span() {
        type Store = fn(&mut [u8], u8);
        let ways: [(&str, Store); 3] =
            [("set_bytes", set_bytes), ("blocks", store_span::<true>), ("memset", store_span::<false>)];
        for (way, store) in ways {
            for start in 0..24 {
                for len in 0..=600 {
                    let mut row = [0u8; 640];
                    store(&mut row[start..start + len], 9);
                    let mut expected = [0u8; 640];
                    expected[start..start + len].fill(9);
                    assert_eq!(row, expected, "{way}: start {start}, length {len}");
                }
            }
        }
    }
}
