//! How fast the show plays.

/// Frames per second the show is paced at: every second retrace of mode
/// 13h's 70 Hz refresh.
pub const FRAMES_PER_SECOND: u32 = 35;
/// How long a still page stays up in the demo, in frames (3 seconds).
pub const STILL_FRAMES: u32 = 3 * FRAMES_PER_SECOND;
