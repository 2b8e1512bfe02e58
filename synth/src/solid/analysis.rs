//! The per-level analysis of the solid exemplars: colours of every Gaussian-stack level (what
//! the crossbar strips compare), appearance vectors of all images in one shared PCA space, and
//! the 2D synthesizer's 4-diagonal neighbourhood records (what the 3D correction compares in
//! each of the three planes through a voxel).

use super::roles::{SolidExemplars, ROLES};
use crate::appearance::{shared_appearance, APPEARANCE_DIMS};
use crate::feature::feature_map;
use crate::neighbourhood::{exemplar_neighbourhoods, NEIGHBOURHOOD_DIMS};
use crate::stack::{gaussian_stack, scalar_stack};

/// One level of one role.
#[derive(Clone, Debug)]
pub struct RoleLevel {
    /// The stack level's colour per pixel, rounded to 8 bits and packed `r | g << 8 | b << 16`.
    pub colours: Vec<u32>,
    /// Quantized appearance vector per pixel, in the level's shared PCA space.
    pub appearance: Vec<[i8; APPEARANCE_DIMS]>,
    /// The 4-diagonal neighbourhood record per pixel (see `synth/neighbourhood.rs`).
    pub neighbourhoods: Vec<[i8; NEIGHBOURHOOD_DIMS]>,
}

/// One pyramid level of all three roles.
#[derive(Clone, Debug)]
pub struct SolidLevel {
    /// Coordinate spacing `h_l = 2^(L−l)`.
    pub spacing: u32,
    /// `E_x`, `E_y`, `E_z` at this level (roles played by one image hold equal copies).
    pub roles: [RoleLevel; ROLES],
    /// Fraction of the pooled appearance variance PCA dropped.
    pub residual_variance: f64,
}

/// The analysed solid exemplars.
#[derive(Clone, Debug)]
pub struct SolidAnalysis {
    /// Side of every exemplar.
    pub side: u32,
    /// Which distinct image plays each role (equal indices: equal images), so that work that
    /// depends on the image only is done once.
    pub role_image: [usize; ROLES],
    /// Levels `0..=L`, coarsest first.
    pub levels: Vec<SolidLevel>,
}

/// Packs an 8-bit RGB colour into one word.
pub fn pack_rgb(c: [u8; 3]) -> u32 {
    c[0] as u32 | (c[1] as u32) << 8 | (c[2] as u32) << 16
}

/// Unpacks a colour packed by [`pack_rgb`].
pub fn unpack_rgb(w: u32) -> [u8; 3] {
    [w as u8, (w >> 8) as u8, (w >> 16) as u8]
}

/// Analyses every level of `exemplars` (toroidal: solid exemplars tile).
pub fn analyze_solid(exemplars: &SolidExemplars) -> SolidAnalysis {
    let side = exemplars.side();
    let finest = exemplars.finest_level();
    let stacks: Vec<Vec<Vec<[f32; 3]>>> = exemplars
        .images
        .iter()
        .map(|e| gaussian_stack(e, true))
        .collect();
    // The feature channel of every image, found on the exemplar and blurred with the colours
    // down the stack.
    // None when off or when every image is speckle; an image without structures among
    // images with them has a zero channel.
    let maps: Vec<_> = stacks
        .iter()
        .map(|stack| {
            feature_map(
                &stack[finest as usize],
                side,
                side,
                true,
                exemplars.feature_weight,
                exemplars.feature_mask,
            )
        })
        .collect();
    let feature_stacks: Option<Vec<Vec<Vec<f32>>>> = maps.iter().any(|m| m.active()).then(|| {
        maps.iter()
            .map(|map| scalar_stack(&map.channel, side, side, finest, true))
            .collect()
    });
    let levels = (0..=finest as usize)
        .map(|l| {
            let spacing = 1u32 << (finest - l as u32);
            let images: Vec<&[[f32; 3]]> = stacks.iter().map(|s| s[l].as_slice()).collect();
            let features: Option<Vec<&[f32]>> = feature_stacks
                .as_ref()
                .map(|f| f.iter().map(|s| s[l].as_slice()).collect());
            let (appearance, residual_variance) =
                shared_appearance(&images, features.as_deref(), side, side, spacing, true);
            let per_image: Vec<RoleLevel> = images
                .iter()
                .zip(appearance)
                .map(|(colours, appearance)| RoleLevel {
                    colours: colours
                        .iter()
                        .map(|c| pack_rgb(c.map(|v| v.round().clamp(0.0, 255.0) as u8)))
                        .collect(),
                    neighbourhoods: exemplar_neighbourhoods(&appearance, side, side, spacing),
                    appearance,
                })
                .collect();
            SolidLevel {
                spacing,
                roles: std::array::from_fn(|r| per_image[exemplars.role_image[r]].clone()),
                residual_variance,
            }
        })
        .collect();
    SolidAnalysis {
        side,
        role_image: exemplars.role_image,
        levels,
    }
}

impl SolidAnalysis {
    /// Index `L` of the finest level.
    pub fn finest_level(&self) -> u32 {
        self.levels.len() as u32 - 1
    }
}
