//! The RGBA8 texel word: the colour format of every store and of the blocked perfect hash's
//! payload. It sits below both, so a hash never reaches up into the stores for it.

use glam::Vec4;

/// An RGBA8 word as colour in [0, 1]⁴; 0 (absent) is (0, 0, 0, 0).
pub fn unpack_rgba8(c: u32) -> Vec4 {
    Vec4::new(
        (c & 255) as f32,
        ((c >> 8) & 255) as f32,
        ((c >> 16) & 255) as f32,
        (c >> 24) as f32,
    ) / 255.0
}
