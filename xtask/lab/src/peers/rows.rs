//! A peer's picture read back as spans: every run of painted (non-zero)
//! bytes of its target, row by row, into the [`SpanSink`] the lab judges
//! through, whatever the peer draws into.

use raster::SpanSink;

/// Every run of non-zero bytes of `rows` (`stride` bytes a row, the first
/// `width` of them pixels), as spans into `sink`.
pub fn emit_rows(rows: &[u8], stride: usize, width: usize, color: u8, sink: &mut dyn SpanSink) {
    for (y, row) in rows.chunks_exact(stride).enumerate() {
        emit_row(y as i32, &row[..width], color, sink);
    }
}

/// Every run of non-zero bytes of `row`, row `y`, as spans into `sink`.
pub fn emit_row(y: i32, row: &[u8], color: u8, sink: &mut dyn SpanSink) {
    let width = row.len();
    let mut x = 0;
    while let Some(start) = row[x..].iter().position(|&v| v != 0).map(|i| x + i) {
        let end = row[start..].iter().position(|&v| v == 0).map_or(width, |i| start + i);
        sink.span(y, start as i32, end as i32, color);
        x = end;
        if x == width {
            break;
        }
    }
}
