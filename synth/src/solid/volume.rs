//! A synthesized box of the volume: the coordinate triple of every voxel at every computed
//! level, and the colours and coordinates the output keeps.
//!
//! **Colour rule**: per channel, the median of the three exemplars' colours at the voxel's
//! triple. The candidates make the three agree along the crossbar, so for a consistent triple
//! the median is that common colour; where one exemplar sees a structure the other two do not
//! (a feature seen edge-on, or a lattice channel constant in one slice direction), the two that
//! agree win, where a mean would blend a ghost of the third into the result. It also never
//! invents a colour outside the exemplars' range along any channel, and it treats the three
//! axes alike, so no slice direction is favoured.

use super::plan::VolumeBox;
use super::relief::{voxel_texel, SolidRelief};
use super::roles::SolidExemplars;
use crate::{SynthError, SynthResult};

/// Largest side of a synthesized box.
pub const MAX_VOLUME_SIDE: u32 = 1024;

/// Largest magnitude of a box origin (absolute positions and padding stay inside `i32`).
pub const MAX_VOLUME_ORIGIN: i32 = 1 << 28;

/// Triples of one level over the box computed there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelTriples {
    /// The computed box (window plus padding, in this level's absolute positions).
    pub region: VolumeBox,
    /// Packed exemplar coordinates `(c_x, c_y, c_z)` per voxel, x fastest.
    pub triples: Vec<[u32; 3]>,
}

/// A synthesized box.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SolidSynthesis {
    /// The requested box of the finest level.
    pub window: VolumeBox,
    /// Levels (coarsest first); a synthesizer asked not to keep them holds only the finest.
    pub levels: Vec<LevelTriples>,
}

impl SolidSynthesis {
    /// The triples of the requested box, x fastest (the padding cut away).
    pub fn window_triples(&self) -> Vec<[u32; 3]> {
        let finest = self
            .levels
            .last()
            .expect("a synthesis has its finest level");
        (0..self.window.voxels())
            .map(|i| finest.triples[finest.region.index(self.window.position(i))])
            .collect()
    }

    /// The window's RGBA8 texels as the stores receive them: the median rule per byte, the
    /// relief code in alpha when `relief` is given (255 otherwise).
    pub fn texels(&self, exemplars: &SolidExemplars, relief: Option<&SolidRelief>) -> Vec<u32> {
        self.window_triples()
            .into_iter()
            .map(|t| voxel_texel(exemplars, relief, t))
            .collect()
    }

    /// The window's colours by the median rule (module docs).
    pub fn colours(&self, exemplars: &SolidExemplars) -> Vec<[u8; 3]> {
        self.window_triples()
            .into_iter()
            .map(|t| voxel_colour(exemplars, t))
            .collect()
    }
}

/// The colour of a voxel with triple `t`: per channel the median of the three exemplars (the
/// RGB of [`voxel_texel`], the rule the stores receive).
pub fn voxel_colour(exemplars: &SolidExemplars, t: [u32; 3]) -> [u8; 3] {
    let w = voxel_texel(exemplars, None, t);
    [w as u8, (w >> 8) as u8, (w >> 16) as u8]
}

/// The middle one of three values.
pub(super) fn median3(a: u8, b: u8, c: u8) -> u8 {
    a.max(b).min(a.min(b).max(c))
}

/// Checks a requested box.
///
/// # Errors
/// [`SynthError::Parameter`] naming the field and its limit.
pub fn check_box(window: VolumeBox) -> SynthResult<()> {
    for (a, &s) in window.size.iter().enumerate() {
        if !(1..=MAX_VOLUME_SIDE).contains(&s) {
            return Err(SynthError::Parameter {
                name: ["volume size x", "volume size y", "volume size z"][a],
                value: s.to_string(),
                limit: format!("must lie in 1..={MAX_VOLUME_SIDE}"),
            });
        }
    }
    for o in window.origin {
        if o.unsigned_abs() > MAX_VOLUME_ORIGIN as u32 {
            return Err(SynthError::Parameter {
                name: "volume offset",
                value: o.to_string(),
                limit: format!(
                    "each component must lie in -{MAX_VOLUME_ORIGIN}..={MAX_VOLUME_ORIGIN}"
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn median_of_three() {
        let m = super::median3;
        for (a, b, d, want) in [
            (1, 2, 3, 2),
            (3, 1, 2, 2),
            (2, 3, 1, 2),
            (5, 5, 0, 5),
            (0, 9, 9, 9),
        ] {
            assert_eq!(m(a, b, d), want);
        }
    }
}
