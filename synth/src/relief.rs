//! The relief channel: the exemplar's feature distance (`crate::feature`) as one byte per
//! pixel, looked up through the synthesized coordinates like the colour and stored in the
//! alpha byte of every store's RGBA8 texel, where a path tracer reads its gradient as a bump.
//!
//! **Why the alpha byte.** Every store already keeps 4 bytes per texel and every colour
//! texture left alpha at 255, so the channel costs no memory, no second lookup and no second
//! store to keep in step with the colours (lazy requests fill both in one write). The octree
//! reserves alpha 0 and 1 for its tags (empty, child pointer), so codes run over
//! [`RELIEF_CODE_MIN`]..=255: 254 levels over the clamped distance's range (at most ±16
//! pixels at 256²: steps of 0.13 px).
//!
//! **The value.** The clamped signed distance `d` (pixels, negative inside features, ±`clamp`)
//! maps linearly to a code: features (cracks, veins, mortar) are low, the matter farthest from
//! them high, so a relief makes features grooves with sloping walls `clamp` pixels wide and
//! flat ground beyond. Unlike the synthesis's feature channel, the distance is kept for
//! speckle too (weight and reach do not apply): a fine relief is still a relief.
//!
//! **The rule across the three roles** is the colour's: the median of the three exemplars'
//! codes at the voxel's triple (`solid::volume`), so the channel and the colour come from the
//! same agreement of the three slices.

use crate::exemplar::Exemplar;
use crate::feature::{feature_map, FeatureMask};

/// Smallest relief code: alpha values below are the octree's tags.
pub const RELIEF_CODE_MIN: u8 = 2;

/// The alpha byte of a texel without relief (a colour texture).
pub const NO_RELIEF: u8 = 255;

/// One image's relief channel.
#[derive(Clone, Debug, PartialEq)]
pub struct ReliefMap {
    /// Row-major codes, [`RELIEF_CODE_MIN`]..=255.
    pub codes: Vec<u8>,
    /// The distance's clamp in pixels: codes span `-clamp..=clamp`.
    pub clamp: f32,
}

/// The code of a clamped signed distance `d` (pixels) with clamp `clamp`.
pub fn relief_code(d: f32, clamp: f32) -> u8 {
    let t = ((d + clamp) / (2.0 * clamp)).clamp(0.0, 1.0);
    let span = f32::from(255 - RELIEF_CODE_MIN);
    RELIEF_CODE_MIN + (t * span).round() as u8
}

/// The distance in pixels a code stands for (the inverse of [`relief_code`], to its step).
pub fn relief_distance(code: u8, clamp: f32) -> f32 {
    let span = f32::from(255 - RELIEF_CODE_MIN);
    (f32::from(code.max(RELIEF_CODE_MIN) - RELIEF_CODE_MIN) / span) * 2.0 * clamp - clamp
}

/// Pixels of distance per unit of the alpha channel (`code / 255` as a store reads it): the
/// factor from the stored channel's gradient to the distance's.
pub fn relief_pixels_per_alpha(clamp: f32) -> f32 {
    2.0 * clamp * 255.0 / f32::from(255 - RELIEF_CODE_MIN)
}

/// The relief channel of `image`, whose distances wrap when it tiles (`toroidal`; solid
/// exemplars always do).
pub fn relief_map(image: &Exemplar, toroidal: bool, mask: FeatureMask) -> ReliefMap {
    let rgb: Vec<[f32; 3]> = image.rgb.iter().map(|c| c.map(f32::from)).collect();
    let map = feature_map(&rgb, image.width, image.height, toroidal, 100, mask);
    ReliefMap {
        codes: map
            .distance
            .iter()
            .map(|&d| relief_code(d, map.clamp))
            .collect(),
        clamp: map.clamp,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_span_the_clamp_and_invert() {
        let clamp = 8.0;
        assert_eq!(relief_code(-clamp, clamp), RELIEF_CODE_MIN);
        assert_eq!(relief_code(clamp, clamp), 255);
        assert_eq!(relief_code(-100.0, clamp), RELIEF_CODE_MIN);
        let step = 2.0 * clamp / f32::from(255 - RELIEF_CODE_MIN);
        for i in 0..=64 {
            let d = -clamp + 2.0 * clamp * i as f32 / 64.0;
            assert!((relief_distance(relief_code(d, clamp), clamp) - d).abs() <= step / 2.0 + 1e-4);
        }
        // Alpha as the store reads it (code / 255), scaled back to pixels.
        let a = |d: f32| f32::from(relief_code(d, clamp)) / 255.0;
        let slope = (a(4.0) - a(-4.0)) * relief_pixels_per_alpha(clamp) / 8.0;
        assert!((slope - 1.0).abs() < 0.02, "{slope}");
    }

    #[test]
    fn cracks_are_grooves() {
        // Dark cracks 3 pixels wide every 32 columns on a light, noisy ground: codes lowest on
        // the cracks, rising away from them, highest far away.
        let (w, h) = (64u32, 64u32);
        let rgb = (0..w * h)
            .map(|i| {
                let noise = ((i.wrapping_mul(2_654_435_761) >> 24) % 24) as u8;
                if (i % w) % 32 >= 19 && (i % w) % 32 <= 21 {
                    [30 + noise; 3]
                } else {
                    [180 + noise; 3]
                }
            })
            .collect();
        let image = Exemplar {
            source: "cracks".into(),
            width: w,
            height: h,
            rgb,
        };
        let map = relief_map(&image, true, FeatureMask::Auto);
        let row: Vec<u8> = (0..w as usize)
            .map(|x| map.codes[10 * w as usize + x])
            .collect();
        assert!(
            row[20] < row[22] && row[22] < row[24] && row[24] < row[26],
            "{row:?}"
        );
        assert!(row[20] < 128 && row[4] == 255, "{row:?}");
    }
}
