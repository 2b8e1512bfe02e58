//! Colour images as three compressed trees, one per channel of the lossless integer YCoCg-R
//! transform: luma carries the detail, and the two chroma channels of smooth or natural images
//! prune far more than R, G and B would. The inverse transform is applied to the decoded
//! values rounded to integers, so lossless trees give the image back exactly.

use super::error::CtreeError;
use super::field::{from_fixed, ScalarField};
use super::tree::{CompressedTree, CtreeOptions};

/// The YCoCg-R transform of an RGB triple: (Y, Co, Cg), Y in 0..=255, Co and Cg in ±255.
pub fn ycocg(rgb: [u8; 3]) -> [i32; 3] {
    let [r, g, b] = rgb.map(i32::from);
    let co = r - b;
    let t = b + (co >> 1);
    let cg = g - t;
    let y = t + (cg >> 1);
    [y, co, cg]
}

/// The inverse of [`ycocg`] on decoded values: each rounded to an integer, then the exact
/// integer inverse, clamped to 8 bits (lossless where the trees are).
pub fn rgb_of_ycocg(v: [f32; 3]) -> [u8; 3] {
    let [y, co, cg] = v.map(|c| c.round() as i32);
    let t = y - (cg >> 1);
    let g = cg + t;
    let b = t - (co >> 1);
    let r = b + co;
    [r, g, b].map(|c| c.clamp(0, 255) as u8)
}

/// An RGB image compressed as three trees (Y, Co, Cg).
#[derive(Clone, Debug)]
pub struct ColourTrees {
    /// The trees of Y, Co and Cg.
    pub channels: [CompressedTree; 3],
}

impl ColourTrees {
    /// Compresses `rgb` (`width`×`height` texels, 3 bytes each, rows first), every channel at
    /// the options' step.
    pub fn build(
        name: &str,
        rgb: &[u8],
        width: u32,
        height: u32,
        options: &CtreeOptions,
    ) -> Result<ColourTrees, CtreeError> {
        let texels = (width * height) as usize;
        if rgb.len() != 3 * texels {
            return Err(CtreeError::Field {
                name: name.into(),
                why: format!(
                    "has {} bytes for {width}×{height} RGB texels ({} expected)",
                    rgb.len(),
                    3 * texels
                ),
            });
        }
        let mut planes = [vec![], vec![], vec![]];
        for t in rgb.chunks_exact(3) {
            let v = ycocg([t[0], t[1], t[2]]);
            for (plane, value) in planes.iter_mut().zip(v) {
                plane.push(value as f32);
            }
        }
        let mut trees = Vec::with_capacity(3);
        for (plane, channel) in planes.into_iter().zip(["Y", "Co", "Cg"]) {
            let field =
                ScalarField::new(&format!("{name} ({channel})"), 2, [width, height, 1], plane)?;
            trees.push(CompressedTree::build(&field, options)?);
        }
        let [y, co, cg]: [CompressedTree; 3] = trees.try_into().expect("three channels");
        Ok(ColourTrees {
            channels: [y, co, cg],
        })
    }

    /// Bytes of the three trees.
    pub fn size_bytes(&self) -> u64 {
        self.channels.iter().map(CompressedTree::size_bytes).sum()
    }

    /// Every texel decoded to RGB8, rows first.
    pub fn decode(&self) -> Vec<u8> {
        let planes: Vec<Vec<f32>> = self.channels.iter().map(|t| t.decode()).collect();
        (0..planes[0].len())
            .flat_map(|i| rgb_of_ycocg([planes[0][i], planes[1][i], planes[2][i]]))
            .collect()
    }
}

/// A decoded grey value (fixed point) as an 8-bit level, rounded and clamped.
pub fn grey_of_fixed(v: i32) -> u8 {
    from_fixed(v).round().clamp(0.0, 255.0) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ycocg_r_is_lossless_on_every_grey_and_corner() {
        for rgb in [
            [0, 0, 0],
            [255, 255, 255],
            [255, 0, 0],
            [0, 255, 0],
            [0, 0, 255],
        ]
        .into_iter()
        .chain((0..=255).map(|v| [v, v, v]))
        .chain((0..=255).map(|v| [v, 255 - v, v / 3]))
        {
            let v = ycocg(rgb);
            assert_eq!(rgb_of_ycocg(v.map(|c| c as f32)), rgb, "{rgb:?}");
        }
    }
}
