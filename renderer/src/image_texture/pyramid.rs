//! An image texture and its MIP pyramid, 8 bits per channel as the device stores it.

use super::ImageError;
use crate::glint::NormalExample;
use glam::{Vec3, Vec4};
use std::path::Path;

/// Longest edge of an image texture: a 8192² RGBA image with its levels is 358 MB, beyond
/// which a binding of lavapipe (128 MiB) cannot hold one image.
pub const MAX_IMAGE_EDGE: u32 = 8192;
/// Most texels (all levels of all images of a scene): one 128 MiB storage buffer of RGBA8.
pub const MAX_IMAGE_TEXELS: u64 = (128 << 20) / 4;

/// How a texel's four bytes are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageEncoding {
    /// sRGB colour and linear alpha: decoded to linear before filtering.
    SrgbColor,
    /// A tangent-space normal, xyz = 2·rgb − 1, +y towards +v (OpenGL's convention, the one
    /// MikkTSpace bakers write). Levels above 0 hold the unnormalized mean of the normals they
    /// cover: plain MIP filtering, whose shortening the renderer normalizes away.
    Normal,
}

impl ImageEncoding {
    /// The device code (`IMAGE_ENCODING_*` of `shader_constants`).
    pub fn code(self) -> u32 {
        match self {
            ImageEncoding::SrgbColor => crate::shader_constants::IMAGE_ENCODING_SRGB,
            ImageEncoding::Normal => crate::shader_constants::IMAGE_ENCODING_NORMAL,
        }
    }
}

/// An image with every MIP level down to 1×1, texels as decoded values (linear colour, or the
/// normal's xyz in w-less form) quantized to 8 bits exactly as uploaded.
#[derive(Clone, Debug)]
pub struct ImageTexture {
    /// Where it came from (for messages).
    pub name: String,
    /// How texels are read.
    pub encoding: ImageEncoding,
    /// Level 0 width.
    pub width: u32,
    /// Level 0 height.
    pub height: u32,
    /// Packed RGBA8 texels of each level, row by row, row 0 at the image's top (v = 1).
    pub levels: Vec<Vec<u32>>,
}

/// Dimensions of level `l` of a `width`×`height` image: halved and floored, at least 1.
pub fn level_size(width: u32, height: u32, l: usize) -> (u32, u32) {
    ((width >> l).max(1), (height >> l).max(1))
}

fn pack(v: Vec4) -> u32 {
    let q = |x: f32| ((x.clamp(0.0, 1.0) * 255.0).round() as u32) & 0xff;
    q(v.x) | q(v.y) << 8 | q(v.z) << 16 | q(v.w) << 24
}

/// The four bytes of a packed texel in [0, 1].
pub fn unpack(t: u32) -> Vec4 {
    Vec4::new(
        (t & 0xff) as f32,
        (t >> 8 & 0xff) as f32,
        (t >> 16 & 0xff) as f32,
        (t >> 24) as f32,
    ) / 255.0
}

pub(super) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

impl ImageTexture {
    /// Reads an albedo image (PNG, JPEG, any size with edges up to [`MAX_IMAGE_EDGE`]; grey or
    /// colour, with or without alpha) as sRGB colour.
    ///
    /// # Errors
    /// An unreadable file or an edge out of range, naming the file.
    pub fn load_color(file: &Path) -> Result<ImageTexture, ImageError> {
        let image = image::open(file)
            .map_err(|e| ImageError::Read {
                file: file.to_path_buf(),
                problem: e.to_string(),
            })?
            .to_rgba8();
        let (width, height) = image.dimensions();
        if width == 0 || height == 0 || width.max(height) > MAX_IMAGE_EDGE {
            return Err(ImageError::Size {
                file: file.to_path_buf(),
                width,
                height,
                max: MAX_IMAGE_EDGE,
            });
        }
        let texels: Vec<Vec4> = image
            .pixels()
            .map(|p| {
                let c = Vec4::from_array(p.0.map(|b| b as f32 / 255.0));
                Vec4::new(
                    srgb_to_linear(c.x),
                    srgb_to_linear(c.y),
                    srgb_to_linear(c.z),
                    c.w,
                )
            })
            .collect();
        Ok(Self::from_linear(
            file.display().to_string(),
            ImageEncoding::SrgbColor,
            width,
            height,
            texels,
        ))
    }

    /// A normal map from its tangent-space normals (x, y with +y towards +v; z implied),
    /// with plain MIP levels of the mean normal.
    pub fn from_normals(name: &str, example: &NormalExample) -> ImageTexture {
        let size = example.size() as u32;
        let texels = example
            .texels()
            .iter()
            .map(|n| {
                let z = (1.0 - n.length_squared()).max(0.0).sqrt();
                n.extend(z).extend(1.0)
            })
            .collect();
        Self::from_linear(name.to_string(), ImageEncoding::Normal, size, size, texels)
    }

    /// Builds the levels from decoded level-0 values: each level averages the 2×2 texels below
    /// it (the last row or column of an odd edge is folded into its neighbour's average).
    fn from_linear(
        name: String,
        encoding: ImageEncoding,
        width: u32,
        height: u32,
        texels: Vec<Vec4>,
    ) -> ImageTexture {
        let mut values = vec![texels];
        let mut l = 0;
        while level_size(width, height, l) != (1, 1) {
            let (w, h) = level_size(width, height, l);
            let (nw, nh) = level_size(width, height, l + 1);
            let src = &values[l];
            let mut next = Vec::with_capacity((nw * nh) as usize);
            for y in 0..nh {
                for x in 0..nw {
                    let xs = footprint(x, w, nw);
                    let ys = footprint(y, h, nh);
                    let mut sum = Vec4::ZERO;
                    for &sy in &ys {
                        for &sx in &xs {
                            sum += src[(sy * w + sx) as usize];
                        }
                    }
                    next.push(sum / (xs.len() * ys.len()) as f32);
                }
            }
            values.push(next);
            l += 1;
        }
        let levels = values
            .iter()
            .map(|level| {
                level
                    .iter()
                    .map(|&v| match encoding {
                        ImageEncoding::SrgbColor => pack(Vec4::new(
                            linear_to_srgb(v.x),
                            linear_to_srgb(v.y),
                            linear_to_srgb(v.z),
                            v.w,
                        )),
                        ImageEncoding::Normal => {
                            pack((v.truncate() * 0.5 + Vec3::splat(0.5)).extend(v.w))
                        }
                    })
                    .collect()
            })
            .collect();
        ImageTexture {
            name,
            encoding,
            width,
            height,
            levels,
        }
    }

    /// Texels of every level.
    pub fn texel_count(&self) -> u64 {
        self.levels.iter().map(|l| l.len() as u64).sum()
    }
}

/// The source columns (or rows) that texel `i` of a level `n` wide covers in the level below,
/// `w` wide: 2i and 2i + 1, and the odd edge's last one with the last texel.
fn footprint(i: u32, w: u32, n: u32) -> Vec<u32> {
    if w == 1 {
        return vec![0];
    }
    let mut v = vec![2 * i, 2 * i + 1];
    if i + 1 == n && w % 2 == 1 {
        v.push(w - 1);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn odd_sizes_reach_one_texel_and_every_texel_counts_once() {
        let (w, h) = (5u32, 3u32);
        let texels: Vec<Vec4> = (0..w * h).map(|i| Vec4::splat(i as f32 / 20.0)).collect();
        let t = ImageTexture::from_linear("t".into(), ImageEncoding::Normal, w, h, texels);
        assert_eq!(t.levels.len(), 3);
        assert_eq!(t.levels[1].len(), 2);
        assert_eq!(t.levels[2].len(), 1);
        for x in 0..5 {
            let covered: Vec<u32> = (0..2).flat_map(|i| footprint(i, 5, 2)).collect();
            assert_eq!(covered.iter().filter(|&&c| c == x).count(), 1);
        }
    }

    #[test]
    fn srgb_round_trips_through_linear_at_eight_bits() {
        for b in 0..=255u32 {
            let c = b as f32 / 255.0;
            let back = linear_to_srgb(srgb_to_linear(c));
            assert_eq!((back * 255.0).round() as u32, b);
        }
    }
}
