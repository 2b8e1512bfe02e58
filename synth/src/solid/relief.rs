//! The relief channel of a solid texture (`crate::relief`): one [`ReliefMap`] per distinct
//! image, and the RGBA8 texel every store receives — per byte the median of the three roles'
//! packed texels at the voxel's triple, so the relief code follows the colour's rule.

use super::roles::{SolidExemplars, ROLES};
use super::volume::median3;
use crate::coords::unpack;
use crate::relief::{relief_map, ReliefMap, NO_RELIEF};

/// The relief maps of a solid texture's images.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidRelief {
    /// One map per distinct image (`SolidExemplars::images`).
    pub maps: Vec<ReliefMap>,
}

impl SolidRelief {
    /// The relief of every image of `exemplars`.
    pub fn of(exemplars: &SolidExemplars) -> SolidRelief {
        SolidRelief {
            maps: exemplars
                .images
                .iter()
                .map(|e| relief_map(e, true, exemplars.feature_mask))
                .collect(),
        }
    }

    /// The distance's clamp in pixels (every image has the same side, so the same clamp).
    pub fn clamp(&self) -> f32 {
        self.maps.first().map_or(0.0, |m| m.clamp)
    }
}

/// The packed texel of role `role` at exemplar pixel `(x, y)`: RGB in the low bytes, the relief
/// code (or [`NO_RELIEF`]) in the high byte.
pub fn role_texel(
    exemplars: &SolidExemplars,
    relief: Option<&SolidRelief>,
    role: usize,
    x: u32,
    y: u32,
) -> u32 {
    let [r, g, b] = exemplars.role(role).at(x, y);
    let code = relief.map_or(NO_RELIEF, |rel| {
        rel.maps[exemplars.role_image[role]].codes[(y * exemplars.side() + x) as usize]
    });
    u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16 | u32::from(code) << 24
}

/// The RGBA8 texel of a voxel with triple `t`: per byte (colour and relief alike) the median
/// of the three roles' texels.
pub fn voxel_texel(exemplars: &SolidExemplars, relief: Option<&SolidRelief>, t: [u32; 3]) -> u32 {
    let c: [u32; ROLES] = std::array::from_fn(|r| {
        let (x, y) = unpack(t[r]);
        role_texel(exemplars, relief, r, x, y)
    });
    (0..4).fold(0, |acc, byte| {
        let [a, b, d] = c.map(|w| (w >> (8 * byte)) as u8);
        acc | u32::from(median3(a, b, d)) << (8 * byte)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coords::pack;
    use crate::exemplar::Exemplar;
    use crate::solid::voxel_colour;

    #[test]
    fn texels_carry_the_median_colour_and_code() {
        let side = 16u32;
        let image = Exemplar {
            source: "stripes".into(),
            width: side,
            height: side,
            rgb: (0..side * side)
                .map(|i| {
                    if i % 8 < 2 {
                        [10, 20, 30]
                    } else {
                        [200, 190, 180]
                    }
                })
                .collect(),
        };
        let ex = SolidExemplars::new(image, [None, None, None]).unwrap();
        let relief = SolidRelief::of(&ex);
        for t in [
            [pack(0, 0), pack(3, 5), pack(1, 9)],
            [pack(5, 1), pack(5, 1), pack(0, 2)],
        ] {
            let texel = voxel_texel(&ex, Some(&relief), t);
            let plain = voxel_texel(&ex, None, t);
            let [r, g, b] = voxel_colour(&ex, t);
            assert_eq!(
                plain,
                u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16 | 255 << 24
            );
            assert_eq!(texel & 0xff_ffff, plain & 0xff_ffff);
            let codes = t.map(|c| {
                let (x, y) = unpack(c);
                relief.maps[0].codes[(y * side + x) as usize] as u32
            });
            let mut sorted = codes;
            sorted.sort();
            assert_eq!(texel >> 24, sorted[1], "{codes:?}");
        }
    }
}
