//! Which way each role sees its exemplar: mirrored left-right where the three roles' diagonal
//! preferences could not otherwise coexist in one volume.
//!
//! A sheet or tube shows in the three slice families diagonal signs that multiply to a
//! non-negative number (`quality/diagonal.rs`). An exemplar whose structures prefer the
//! negative diagonal (`ρ < 0`: veins from top left to bottom right, as in granite1 and
//! marble1) in all three roles asks for three negative families, which no structure gives:
//! the synthesis then mixes structures that each contradict one family and the slices lose
//! most of the diagonal (measured: granite1's 128² fit ρ −0.41, its slices' families −0.10 /
//! −0.15 / −0.09, their axis share near an isotropic texture's, so the blockiness figure reads
//! 1.6). Mirroring one
//! role's image (u → side − 1 − u) flips its sign; the product is then positive and the
//! preference can be kept on every axis. A mirrored photograph is a photograph of the same
//! material, so this changes no statistic the slices are scored by except the sign the
//! mirrored role's slices are compared with.
//!
//! Mirroring has a cost too: the mirrored role's strips along its u axis run backwards against
//! the role that shares that axis, and where the exemplar's profiles are not symmetric (relief
//! lit from one side, wood grain) fewer triples agree along it. Measured at 128³ over three
//! seeds (`docs/log/solid.md`, "Diagonal orientation"), the mean SWD ratio and blockiness of the
//! nine axis-seeds, as given → mirrored: granite1 (ρ −0.41) 1.20 → 1.23 and 1.55 → 1.35;
//! marble1 (−0.25) 1.61 → 1.41 and 1.43 → 1.35; walnut (−0.12) 1.21 → 1.18 and 1.07 → 1.03,
//! although walnut's z axis lost in every seed (1.04–1.37 → 1.44–1.48) while x and y gained.
//! On the mean of eight slices per axis (seed 3) the mirror gains on 7 of 9 axes; walnut's z
//! loses 0.11 and granite1's 0.04.
//!
//! The rule ([`Orientation::Auto`]): where the product of the three roles' correlations is
//! negative and every one of them is at least [`MIN_DIAGONAL_CORRELATION`] in size, mirror the
//! role whose correlation is smallest in size; between equals (one image in all roles) `E_y`.
//! [`Orientation::Mirror`] does so at any size.

use super::roles::{SolidExemplars, ROLES, ROLE_NAMES};
use crate::quality::{diagonal_correlation, LinearImage};
use crate::Exemplar;

/// Smallest diagonal correlation, in size, that the rule acts on: a floor under which an
/// image has no diagonal preference to keep (leather, terra, parque1: 0.002–0.024), not a
/// tuned threshold; the smallest one measured to gain on average is walnut's 0.12.
pub const MIN_DIAGONAL_CORRELATION: f64 = 0.05;

/// Whether a role may see its exemplar mirrored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Orientation {
    /// The rule of the module docs.
    #[default]
    Auto,
    /// Every role sees its image as given: an ablation that shows what the mirroring gains.
    Keep,
    /// The rule at any size of the correlations (only their signs).
    Mirror,
}

impl Orientation {
    /// Its name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Auto => "auto",
            Orientation::Keep => "keep",
            Orientation::Mirror => "mirror",
        }
    }
}

/// What the rule did, for the run to print.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Mirroring {
    /// The rule asked for.
    pub orientation: Orientation,
    /// Each role's diagonal correlation as given.
    pub correlations: [f64; ROLES],
    /// The role that sees its image mirrored left-right, if any.
    pub mirrored: Option<usize>,
}

impl std::fmt::Display for Mirroring {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b, c] = self.correlations;
        write!(f, "diagonal correlation {a:+.3} / {b:+.3} / {c:+.3}: ")?;
        match self.mirrored {
            Some(r) => write!(
                f,
                "{} mirrored left-right (three roles with these signs have no consistent 3D structure: a sheet shows the same diagonal sign in at most two of the three slice families; docs/solid.md, \"Diagonal orientation\")",
                ROLE_NAMES[r]
            ),
            None if self.orientation == Orientation::Keep => {
                write!(f, "every role as given (--orientation keep)")
            }
            None if self.correlations.iter().product::<f64>() < 0.0 => write!(
                f,
                "every role as given (a diagonal preference under {MIN_DIAGONAL_CORRELATION} is not worth a mirrored role; --orientation mirror makes one)"
            ),
            None => write!(f, "every role as given"),
        }
    }
}

/// The role to mirror for correlations `rho` each at least `min` in size (module docs), if
/// any.
pub fn role_to_mirror(rho: [f64; ROLES], min: f64) -> Option<usize> {
    let product: f64 = rho.iter().product();
    if product >= 0.0 || rho.iter().any(|r| r.abs() < min) {
        return None;
    }
    // Smallest in size; E_y first among equals.
    [1, 0, 2].into_iter().reduce(|best, r| {
        if rho[r].abs() < rho[best].abs() {
            r
        } else {
            best
        }
    })
}

/// `exemplar` mirrored left-right.
pub fn mirrored(exemplar: &Exemplar) -> Exemplar {
    let (w, h) = (exemplar.width as usize, exemplar.height as usize);
    let rgb = (0..w * h)
        .map(|k| exemplar.rgb[(k / w) * w + (w - 1 - k % w)])
        .collect();
    Exemplar {
        rgb,
        ..exemplar.clone()
    }
}

/// The correlation of an exemplar's luminance gradients along the diagonal.
pub fn exemplar_diagonal(exemplar: &Exemplar) -> f64 {
    diagonal_correlation(&LinearImage::from_rgb8(
        &exemplar.rgb,
        exemplar.width as usize,
        exemplar.height as usize,
    ))
}

impl SolidExemplars {
    /// The same exemplars with each role's image oriented by `orientation` (module docs), and
    /// what was done. A mirrored role whose image other roles share gets its own copy.
    pub fn with_orientation(mut self, orientation: Orientation) -> (SolidExemplars, Mirroring) {
        let correlations: [f64; ROLES] = std::array::from_fn(|r| exemplar_diagonal(self.role(r)));
        let role = match orientation {
            Orientation::Auto => role_to_mirror(correlations, MIN_DIAGONAL_CORRELATION),
            Orientation::Mirror => role_to_mirror(correlations, 0.0),
            Orientation::Keep => None,
        };
        if let Some(r) = role {
            let image = mirrored(self.role(r));
            let i = self.role_image[r];
            if (0..ROLES).any(|o| o != r && self.role_image[o] == i) {
                self.role_image[r] = self.images.len();
                self.images.push(image);
            } else {
                self.images[i] = image;
            }
        }
        (
            self,
            Mirroring {
                orientation,
                correlations,
                mirrored: role,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stripes(sign: i64, name: &str) -> Exemplar {
        let n = 32usize;
        let rgb = (0..n * n)
            .map(|k| {
                let (x, y) = ((k % n) as i64, (k / n) as i64);
                let t = (x + sign * y).rem_euclid(8);
                let v = if t < 3 { 30 } else { 210 } + (k % 7) as u8;
                [v, v / 2, 255 - v]
            })
            .collect();
        Exemplar::from_rgb(name, n as u32, n as u32, rgb).unwrap()
    }

    #[test]
    fn the_rule_mirrors_one_role_only_where_the_signs_cannot_coexist() {
        let min = MIN_DIAGONAL_CORRELATION;
        assert_eq!(role_to_mirror([-0.3; 3], min), Some(1));
        assert_eq!(role_to_mirror([0.3; 3], min), None);
        assert_eq!(role_to_mirror([-0.3, -0.3, 0.3], min), None);
        assert_eq!(role_to_mirror([-0.3, 0.4, 0.25], min), Some(2));
        assert_eq!(role_to_mirror([-0.3, -0.04, -0.3], min), None);
        assert_eq!(role_to_mirror([-0.3, -0.04, -0.3], 0.0), Some(1));
        assert_eq!(role_to_mirror([0.0; 3], 0.0), None);
    }

    #[test]
    fn a_negative_diagonal_gets_a_mirrored_copy_for_e_y_and_a_positive_one_is_kept() {
        let negative = stripes(-1, "falling");
        let e = SolidExemplars::new(negative.clone(), [None, None, None]).unwrap();
        let (e, report) = e.with_orientation(Orientation::Auto);
        assert_eq!(report.mirrored, Some(1));
        assert!(report.correlations.iter().all(|&r| r < -0.5), "{report:?}");
        assert_eq!(e.images.len(), 2);
        assert_eq!(e.role(0).rgb, negative.rgb);
        assert_eq!(e.role(2).rgb, negative.rgb);
        assert_eq!(mirrored(e.role(1)).rgb, negative.rgb);
        assert!(exemplar_diagonal(e.role(1)) > 0.5);
        assert!(report.to_string().contains("E_y mirrored"), "{report}");

        let (kept, report) = SolidExemplars::new(negative.clone(), [None, None, None])
            .unwrap()
            .with_orientation(Orientation::Keep);
        assert_eq!((report.mirrored, kept.images.len()), (None, 1));
        let (_, report) = SolidExemplars::new(negative.clone(), [None, None, None])
            .unwrap()
            .with_orientation(Orientation::Mirror);
        assert_eq!(report.mirrored, Some(1));

        let positive = stripes(1, "rising");
        let (e, report) = SolidExemplars::new(positive.clone(), [None, None, None])
            .unwrap()
            .with_orientation(Orientation::Auto);
        assert_eq!((report.mirrored, e.images.len()), (None, 1));

        // Three images, E_z alone negative: the product is negative, and one role (each has
        // its own image) is mirrored in place.
        let weak = stripes(-1, "weak-falling");
        let (e, report) = SolidExemplars::new(
            positive.clone(),
            [Some(positive.clone()), Some(positive), Some(weak.clone())],
        )
        .unwrap()
        .with_orientation(Orientation::Auto);
        assert!(report.mirrored.is_some());
        let r = report.mirrored.unwrap();
        assert_eq!(e.images.len(), 3);
        assert!(exemplar_diagonal(e.role(r)) * report.correlations[r] < 0.0);
    }
}
