//! The three exemplar roles of solid synthesis and the fixed map between each role's image
//! axes and the world axes, which the candidates, the synthesizer and the slices all use.
//!
//! `E_x` is the slice perpendicular to world x, `E_y` perpendicular to y, `E_z` perpendicular
//! to z. Image coordinates `(u, v)` (u to the right, v down) map to world axes as
//!
//! ```text
//!     role  normal  u  v
//!     E_x   x       y  z
//!     E_y   y       x  z
//!     E_z   z       x  y
//! ```
//!
//! so two roles always share exactly one world axis (the "crossbar" line where their
//! neighbourhoods intersect): `E_x`/`E_y` share z (both along v), `E_x`/`E_z` share y (u of
//! `E_x`, v of `E_z`), `E_y`/`E_z` share x (both along u).

use crate::feature::{FeatureMask, DEFAULT_FEATURE_WEIGHT, MAX_FEATURE_WEIGHT};
use crate::{Exemplar, SynthError, SynthResult};

/// Number of roles (and of world axes).
pub const ROLES: usize = 3;

/// Names of the roles, for messages and file names.
pub const ROLE_NAMES: [&str; ROLES] = ["E_x", "E_y", "E_z"];

/// The world axis (0 = x, 1 = y, 2 = z) of image axis `u` (index 0) and `v` (index 1) of
/// each role.
pub const ROLE_AXES: [[usize; 2]; ROLES] = [[1, 2], [0, 2], [0, 1]];

/// Smallest exemplar side of solid synthesis (as in 2D: at least 5 pyramid levels).
pub const MIN_SOLID_SIDE: u32 = 16;

/// Largest exemplar side: the candidate search compares strips of every pixel with strips of
/// every other, so its time grows with the fourth power of the side (256²: 65536 × 65536
/// strip pairs per search and level, 16 times 128²'s). Larger images are resampled to this
/// by `fit.rs`.
pub const MAX_SOLID_SIDE: u32 = 256;

/// The world-space offset `d` seen in the image plane of `role`: its `(u, v)` components.
pub fn project(role: usize, d: [i32; 3]) -> [i32; 2] {
    let [a, b] = ROLE_AXES[role];
    [d[a], d[b]]
}

/// The image axis (0 = u, 1 = v) along which world `axis` runs in `role`'s image; `None` for
/// the role's normal.
pub fn image_axis(role: usize, axis: usize) -> Option<usize> {
    ROLE_AXES[role].iter().position(|&a| a == axis)
}

/// The world axis two different roles share.
pub fn shared_axis(a: usize, b: usize) -> usize {
    debug_assert_ne!(a, b);
    3 - a - b
}

/// The exemplars of a solid synthesis: distinct images and which image plays each role.
#[derive(Clone, Debug)]
pub struct SolidExemplars {
    /// Distinct images, in the order they were given.
    pub images: Vec<Exemplar>,
    /// Index into `images` of each role's image.
    pub role_image: [usize; ROLES],
    /// Weight of the feature-distance channel in the appearance space, in percent of the
    /// colour's standard deviation (`synth/feature.rs`; 0: colour only).
    pub feature_weight: u32,
    /// Which threshold finds the features (`synth/feature.rs`).
    pub feature_mask: FeatureMask,
}

impl SolidExemplars {
    /// `main` plays every role that `roles` leaves `None` (the common case: one image for all
    /// three). Images are checked for solid synthesis: square, a power-of-two side in
    /// [`MIN_SOLID_SIDE`]..=[`MAX_SOLID_SIDE`], and all of the same side, because every role
    /// shares each of its axes with another role.
    ///
    /// # Errors
    /// [`SynthError::Size`] or [`SynthError::Parameter`] naming the image and the limit.
    pub fn new(main: Exemplar, roles: [Option<Exemplar>; ROLES]) -> SynthResult<SolidExemplars> {
        check_side(&main)?;
        let mut images = vec![main];
        let mut role_image = [0; ROLES];
        for (role, given) in roles.into_iter().enumerate() {
            if let Some(image) = given {
                check_side(&image)?;
                if image.width != images[0].width {
                    return Err(SynthError::Parameter {
                        name: ["--ex", "--ey", "--ez"][role],
                        value: format!(
                            "{} is {}x{}",
                            image.source.display(),
                            image.width,
                            image.height
                        ),
                        limit: format!(
                            "every exemplar of a solid must have the same side as {} ({}x{}), since each role shares an axis with the others",
                            images[0].source.display(),
                            images[0].width,
                            images[0].height
                        ),
                    });
                }
                role_image[role] = images.len();
                images.push(image);
            }
        }
        // The main image is unused when all three roles were given.
        if role_image.iter().all(|&i| i != 0) {
            images.remove(0);
            role_image.iter_mut().for_each(|i| *i -= 1);
        }
        Ok(SolidExemplars {
            images,
            role_image,
            feature_weight: DEFAULT_FEATURE_WEIGHT,
            feature_mask: FeatureMask::Auto,
        })
    }

    /// The same exemplars with the feature-distance channel at `percent` % of the colour's
    /// standard deviation.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] past [`MAX_FEATURE_WEIGHT`].
    pub fn with_feature_weight(mut self, percent: u32) -> SynthResult<SolidExemplars> {
        if percent > MAX_FEATURE_WEIGHT {
            return Err(SynthError::Parameter {
                name: "--feature-weight",
                value: percent.to_string(),
                limit: format!(
                    "0..={MAX_FEATURE_WEIGHT} (percent of the colour's standard deviation; past that the colour is drowned)"
                ),
            });
        }
        self.feature_weight = percent;
        Ok(self)
    }

    /// The same exemplars with their features found by `mask`.
    pub fn with_feature_mask(mut self, mask: FeatureMask) -> SolidExemplars {
        self.feature_mask = mask;
        self
    }

    /// Side of every exemplar.
    pub fn side(&self) -> u32 {
        self.images[0].width
    }

    /// The image of `role`.
    pub fn role(&self, role: usize) -> &Exemplar {
        &self.images[self.role_image[role]]
    }

    /// Index `L` of the finest pyramid level, `log2(side)`.
    pub fn finest_level(&self) -> u32 {
        self.side().ilog2()
    }
}

fn check_side(e: &Exemplar) -> SynthResult<()> {
    if e.width != e.height
        || !e.width.is_power_of_two()
        || !(MIN_SOLID_SIDE..=MAX_SOLID_SIDE).contains(&e.width)
    {
        return Err(SynthError::Parameter {
            name: "solid exemplar size",
            value: format!("{} is {}x{}", e.source.display(), e.width, e.height),
            limit: format!(
                "solid synthesis needs square exemplars with a power-of-two side in {MIN_SOLID_SIDE}..={MAX_SOLID_SIDE} (the pyramid levels halve the side exactly; the candidate search grows with the fourth power of the side); `lazysolid solid` fits any image to that (--fit)"
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pair_of_roles_shares_one_axis_in_both_images() {
        for a in 0..ROLES {
            for b in 0..ROLES {
                if a == b {
                    continue;
                }
                let s = shared_axis(a, b);
                assert!(image_axis(a, s).is_some() && image_axis(b, s).is_some());
                assert_eq!(image_axis(a, a), None);
            }
        }
        assert_eq!(project(0, [1, 2, 3]), [2, 3]);
        assert_eq!(project(1, [1, 2, 3]), [1, 3]);
        assert_eq!(project(2, [1, 2, 3]), [1, 2]);
    }
}
