//! The one exemplar preparation: a recipe's images read, fitted to one side, given the
//! feature channel and oriented.

use super::SolidRecipe;
use crate::fit::{load_solid, ExemplarFit};
use crate::solid::{analyze_solid, Mirroring, SolidAnalysis, SolidExemplars};
use crate::SynthResult;

/// A recipe's exemplars, ready for analysis, with what was done to each image (for the run
/// to print: every command reports the fit and the orientation the same way).
#[derive(Clone, Debug)]
pub struct SolidSources {
    /// The recipe they were made from.
    pub recipe: SolidRecipe,
    /// The exemplars the synthesis uses: fitted, with the feature channel, oriented.
    pub exemplars: SolidExemplars,
    /// The same before the orientation rule: what a mirrored role's slices are compared with
    /// when the ablation keeps every image as given.
    pub given: SolidExemplars,
    /// How each image in use was fitted, in the order of `SolidExemplars::images` as given.
    pub fits: Vec<ExemplarFit>,
    /// What the orientation rule did.
    pub mirroring: Mirroring,
}

impl SolidRecipe {
    /// Reads and prepares the recipe's exemplars: the main image fitted by `fit` (to
    /// `exemplar_side` when given), each role image fitted to the side the main image got,
    /// then the feature channel, then the orientation rule.
    ///
    /// # Errors
    /// An image that cannot be read or fitted, images of different sides, or a feature
    /// weight past its limit: each error names the image or the parameter.
    pub fn load(&self) -> SynthResult<SolidSources> {
        let main = load_solid(&self.exemplar, self.fit, self.exemplar_side)?;
        let side = main.exemplar.width;
        let mut fits = vec![main.fit];
        let mut given = [None, None, None];
        for (slot, path) in given.iter_mut().zip(&self.roles) {
            if let Some(path) = path {
                let fitted = load_solid(path, self.fit, Some(side))?;
                fits.push(fitted.fit);
                *slot = Some(fitted.exemplar);
            }
        }
        // The main image is unused when all three roles are given (SolidExemplars drops it).
        if fits.len() == 4 {
            fits.remove(0);
        }
        let given = SolidExemplars::new(main.exemplar, given)?
            .with_feature_weight(self.feature_weight)?
            .with_feature_mask(self.feature_mask);
        let (exemplars, mirroring) = given.clone().with_orientation(self.orientation);
        Ok(SolidSources {
            recipe: self.clone(),
            exemplars,
            given,
            fits,
            mirroring,
        })
    }
}

impl SolidSources {
    /// The exemplars' analysis (pyramids and appearance vectors per role), on the CPU.
    pub fn analyze(&self) -> SolidAnalysis {
        analyze_solid(&self.exemplars)
    }
}
