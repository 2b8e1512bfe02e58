//! Decoder of GIMP `.pat` patterns, the classic tileable textures shipped with GIMP: a
//! big-endian header (header size, version 1, width, height, bytes per pixel, magic `GPAT`,
//! then a NUL-terminated name filling the header) followed by raw row-major pixels.

use super::error::{SynthError, SynthResult};
use std::path::Path;

/// Fixed part of the header: five `u32` and the 4-byte magic.
const FIXED_HEADER: usize = 24;

/// Largest side a pattern header may announce (guards the pixel allocation).
const MAX_PATTERN_SIDE: u32 = 8192;

/// A decoded pattern: interleaved 8-bit samples with `channels` per pixel.
#[derive(Debug)]
pub struct Pattern {
    /// The name stored in the header.
    pub name: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Bytes per pixel (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA).
    pub channels: u32,
    /// `width * height * channels` samples.
    pub pixels: Vec<u8>,
}

fn be_u32(bytes: &[u8], at: usize) -> u32 {
    u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// Decodes the pattern `bytes` read from `path` (used in every error).
///
/// # Errors
/// [`SynthError::PatternHeader`] naming the header field and its limit, or
/// [`SynthError::Channels`] for an unsupported pixel size.
pub fn decode_pattern(path: &Path, bytes: &[u8]) -> SynthResult<Pattern> {
    let header = |field, value: String, limit: String| SynthError::PatternHeader {
        path: path.to_owned(),
        field,
        value,
        limit,
    };
    if bytes.len() < FIXED_HEADER {
        return Err(header(
            "header_size",
            format!("cut short at {} bytes", bytes.len()),
            format!("the fixed header alone takes {FIXED_HEADER} bytes"),
        ));
    }
    if &bytes[20..24] != b"GPAT" {
        return Err(header(
            "magic",
            format!("{:?}", String::from_utf8_lossy(&bytes[20..24])),
            "must be \"GPAT\"".into(),
        ));
    }
    let header_size = be_u32(bytes, 0) as usize;
    if header_size < FIXED_HEADER || header_size > bytes.len() {
        return Err(header(
            "header_size",
            header_size.to_string(),
            format!(
                "must lie in {FIXED_HEADER}..={} (the file size)",
                bytes.len()
            ),
        ));
    }
    let version = be_u32(bytes, 4);
    if version != 1 {
        return Err(header(
            "version",
            version.to_string(),
            "only version 1 exists".into(),
        ));
    }
    let (width, height) = (be_u32(bytes, 8), be_u32(bytes, 12));
    for (field, side) in [("width", width), ("height", height)] {
        if side == 0 || side > MAX_PATTERN_SIDE {
            return Err(header(
                field,
                side.to_string(),
                format!("must lie in 1..={MAX_PATTERN_SIDE}"),
            ));
        }
    }
    let channels = be_u32(bytes, 16);
    if !(1..=4).contains(&channels) {
        return Err(SynthError::Channels {
            path: path.to_owned(),
            channels,
        });
    }
    let name_bytes = &bytes[FIXED_HEADER..header_size];
    let name_end = name_bytes
        .iter()
        .position(|&b| b == 0)
        .unwrap_or(name_bytes.len());
    let name = String::from_utf8_lossy(&name_bytes[..name_end]).into_owned();
    let count = width as usize * height as usize * channels as usize;
    let body = &bytes[header_size..];
    if body.len() < count {
        return Err(header(
            "pixels",
            format!("{} bytes after the header", body.len()),
            format!("a {width}x{height} pattern of {channels} byte(s) per pixel needs {count}"),
        ));
    }
    Ok(Pattern {
        name,
        width,
        height,
        channels,
        pixels: body[..count].to_vec(),
    })
}
