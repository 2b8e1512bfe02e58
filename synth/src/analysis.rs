//! Exemplar analysis, a CPU preprocessing step run once per exemplar (like the paper's
//! precomputation): Gaussian stack, quantized appearance vectors and k-coherence sets for every
//! level. Its output is integers only, so the synthesizers that consume it (GPU and CPU) agree
//! exactly.

use super::appearance::{shared_appearance, Appearance, APPEARANCE_DIMS};
use super::coherence::coherence_sets;
use super::error::{SynthError, SynthResult};
use super::exemplar::Exemplar;
use super::feature::{feature_map, FeatureMask, DEFAULT_FEATURE_WEIGHT, MAX_FEATURE_WEIGHT};
use super::neighbourhood::{exemplar_neighbourhoods, NEIGHBOURHOOD_DIMS};
use super::stack::{gaussian_stack, scalar_stack};

/// Largest k of the similarity sets (9k candidates per pixel and correction).
pub const MAX_COHERENCE_K: u32 = 8;

/// Largest spread, in pixels, between the members of a similarity set.
pub const MAX_COHERENCE_SPREAD: u32 = 32;

/// Default size of the similarity sets (the paper's 2: the pixel itself and one other).
pub const DEFAULT_COHERENCE_K: u32 = 2;

/// Default smallest distance between the members of a similarity set. Members 16 pixels apart
/// come from different features of the exemplar rather than the next pixel of the same one,
/// which gives the correction real alternatives. Over seeds 1–16 at 256², against a spread of
/// 8, the mean neighbourhood energy drops by 5 % (leather), 2 % (brick) and 13 % (walnut) and
/// rises by 3 % (terra); see docs/synthesis.md, "Similarity-set spread".
pub const DEFAULT_COHERENCE_SPREAD: u32 = 16;

/// Choices of the analysis.
#[derive(Clone, Copy, Debug)]
pub struct AnalysisParams {
    /// Members of each similarity set, the pixel itself included (the paper uses 2).
    pub k: u32,
    /// Smallest toroidal distance between members of a set, in pixels.
    pub spread: u32,
    /// Whether the exemplar tiles (borders wrap) or is clamped at its edges.
    pub toroidal: bool,
    /// Weight of the feature-distance channel in the appearance space, in percent of the
    /// colour's standard deviation (`synth/feature.rs`; 0: colour only). The multiscale
    /// analysis, whose exemplars are related by colour offsets, ignores it.
    pub feature_weight: u32,
    /// Which threshold finds the features the channel measures distances to.
    pub feature_mask: FeatureMask,
}

impl AnalysisParams {
    /// Checks `k` and `spread` against their limits (every analysis, 2D or multiscale).
    ///
    /// # Errors
    /// [`SynthError::Parameter`] naming the field out of range.
    pub fn check(&self) -> SynthResult<()> {
        if !(1..=MAX_COHERENCE_K).contains(&self.k) {
            return Err(SynthError::Parameter {
                name: "k",
                value: self.k.to_string(),
                limit: format!("must lie in 1..={MAX_COHERENCE_K}"),
            });
        }
        if self.spread > MAX_COHERENCE_SPREAD {
            return Err(SynthError::Parameter {
                name: "spread",
                value: self.spread.to_string(),
                limit: format!("must be at most {MAX_COHERENCE_SPREAD}"),
            });
        }
        if self.feature_weight > MAX_FEATURE_WEIGHT {
            return Err(SynthError::Parameter {
                name: "--feature-weight",
                value: self.feature_weight.to_string(),
                limit: format!(
                    "0..={MAX_FEATURE_WEIGHT} (percent of the colour's standard deviation; past that the colour is drowned)"
                ),
            });
        }
        Ok(())
    }
}

impl Default for AnalysisParams {
    fn default() -> Self {
        AnalysisParams {
            k: DEFAULT_COHERENCE_K,
            spread: DEFAULT_COHERENCE_SPREAD,
            toroidal: true,
            feature_weight: DEFAULT_FEATURE_WEIGHT,
            feature_mask: FeatureMask::Auto,
        }
    }
}

/// What synthesis needs of one stack level.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelAnalysis {
    /// Coordinate spacing `h_l = 2^(L−l)` of this level, in exemplar pixels.
    pub spacing: u32,
    /// Quantized appearance vector of every exemplar pixel, row-major.
    pub appearance: Vec<[i8; APPEARANCE_DIMS]>,
    /// The 4-diagonal exemplar neighbourhood of every exemplar pixel, row-major: what the
    /// correction compares each candidate with, precomputed so a candidate is one record.
    pub neighbourhoods: Vec<[i8; NEIGHBOURHOOD_DIMS]>,
    /// `k` packed coordinates per exemplar pixel, the pixel itself first.
    pub coherence: Vec<u32>,
    /// Fraction of the appearance variance PCA dropped at this level.
    pub residual_variance: f64,
}

/// The analysed exemplar.
#[derive(Clone, Debug, PartialEq)]
pub struct ExemplarAnalysis {
    /// Exemplar width.
    pub width: u32,
    /// Exemplar height.
    pub height: u32,
    /// Similarity set size.
    pub k: u32,
    /// Levels `0..=L`, coarsest first.
    pub levels: Vec<LevelAnalysis>,
}

impl ExemplarAnalysis {
    /// Index `L` of the finest level.
    pub fn finest_level(&self) -> u32 {
        self.levels.len() as u32 - 1
    }
}

/// Analyses `exemplar`.
///
/// # Errors
/// [`SynthError::Parameter`] when `k` or `spread` is out of range.
pub fn analyze(exemplar: &Exemplar, params: &AnalysisParams) -> SynthResult<ExemplarAnalysis> {
    params.check()?;
    let (w, h) = (exemplar.width, exemplar.height);
    let finest = exemplar.finest_level();
    let stack = gaussian_stack(exemplar, params.toroidal);
    // The feature channel, found on the exemplar and blurred down the stack with the colours.
    // None when off or when the exemplar is speckle (the analysis is then colour only).
    let map = feature_map(
        &stack[finest as usize],
        w,
        h,
        params.toroidal,
        params.feature_weight,
        params.feature_mask,
    );
    let features = map
        .active()
        .then(|| scalar_stack(&map.channel, w, h, finest, params.toroidal));
    let levels = stack
        .iter()
        .enumerate()
        .map(|(l, colours)| {
            let spacing = 1u32 << (finest - l as u32);
            let feature = features.as_ref().map(|f| [f[l].as_slice()]);
            let (mut vectors, residual_variance) = shared_appearance(
                &[colours],
                feature.as_ref().map(|f| f.as_slice()),
                w,
                h,
                spacing,
                params.toroidal,
            );
            let a = Appearance {
                vectors: vectors.pop().expect("one image in, one out"),
                residual_variance,
            };
            let coherence = coherence_sets(&a.vectors, w, h, params.k, params.spread);
            LevelAnalysis {
                spacing,
                neighbourhoods: exemplar_neighbourhoods(&a.vectors, w, h, spacing),
                appearance: a.vectors,
                coherence,
                residual_variance: a.residual_variance,
            }
        })
        .collect();
    Ok(ExemplarAnalysis {
        width: w,
        height: h,
        k: params.k,
        levels,
    })
}
