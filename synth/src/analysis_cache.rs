//! The exemplar analysis through the on-disk cache (`cache.rs`): keyed by the exemplar's
//! pixels, every analysis parameter and the constants of the analysis code, so a second
//! synthesis of the same exemplar skips the CPU analysis and gets a bit-identical result.
//!
//! The payload holds per level the spacing, the residual variance, the quantized appearance
//! vectors and the similarity sets; the exemplar neighbourhood records, four times the size of
//! the appearance vectors, are rebuilt from those on load (a few milliseconds at 256²).

use super::analysis::{analyze, AnalysisParams, ExemplarAnalysis, LevelAnalysis};
use super::appearance::{APPEARANCE_DIMS, APPEARANCE_QUANT_MAX};
use super::cache::{
    ByteReader, ByteWriter, CacheError, CacheKey, CacheOutcome, DiskCache, KeyBuilder,
};
use super::coherence::MAX_POOL;
use super::error::SynthResult;
use super::exemplar::Exemplar;
use super::neighbourhood::exemplar_neighbourhoods;

/// Cache kind (the entries' subfolder) of exemplar analyses.
pub const ANALYSIS_CACHE_KIND: &str = "synth-analysis";

/// Version of the analysis and of its payload: bumped whenever the analysis computes anything
/// differently (stack, appearance, PCA, quantization, similarity sets) or the encoding
/// changes, so that entries of an older analysis are never read as current.
pub const ANALYSIS_FORMAT_VERSION: u32 = 1;

/// The cache key of `exemplar` analysed with `params`.
pub fn analysis_key(exemplar: &Exemplar, params: &AnalysisParams) -> CacheKey {
    KeyBuilder::new(ANALYSIS_CACHE_KIND, ANALYSIS_FORMAT_VERSION)
        .u32("width", exemplar.width)
        .u32("height", exemplar.height)
        .bytes("rgb", exemplar.rgb.as_flattened())
        .u32("k", params.k)
        .u32("spread", params.spread)
        .bool("toroidal", params.toroidal)
        .u32("feature weight", params.feature_weight)
        .u32("feature rule", super::feature::FEATURE_RULE)
        .u32("feature mask", params.feature_mask.code())
        .u32("appearance dims", APPEARANCE_DIMS as u32)
        .f64("quantization", APPEARANCE_QUANT_MAX)
        .u32("coherence pool", MAX_POOL as u32)
        .finish()
}

/// Encodes `analysis` as a cache payload.
pub fn encode_analysis(analysis: &ExemplarAnalysis) -> Vec<u8> {
    let mut w = ByteWriter::default();
    w.u32(analysis.width);
    w.u32(analysis.height);
    w.u32(analysis.k);
    w.u32(analysis.levels.len() as u32);
    for level in &analysis.levels {
        w.u32(level.spacing);
        w.f64(level.residual_variance);
        w.slice(&level.appearance);
        w.slice(&level.coherence);
    }
    w.into_bytes()
}

/// Decodes a payload of [`encode_analysis`] for `exemplar` analysed with `params`, checking
/// every size and coordinate against them, so that a payload that passed the checksum but
/// does not belong here is refused rather than handed to a synthesizer.
///
/// # Errors
/// [`CacheError::Decode`] naming the first field that does not fit.
pub fn decode_analysis(
    bytes: &[u8],
    exemplar: &Exemplar,
    params: &AnalysisParams,
) -> Result<ExemplarAnalysis, CacheError> {
    let bad = |what: String| CacheError::Decode(what);
    let mut r = ByteReader::new(bytes);
    let (width, height, k) = (r.u32()?, r.u32()?, r.u32()?);
    if (width, height, k) != (exemplar.width, exemplar.height, params.k) {
        return Err(bad(format!(
            "analysis of a {width}x{height} exemplar with k = {k}, expected {}x{} with k = {}",
            exemplar.width, exemplar.height, params.k
        )));
    }
    let count = r.u32()?;
    if count != exemplar.finest_level() + 1 {
        return Err(bad(format!(
            "{count} levels, the exemplar has {}",
            exemplar.finest_level() + 1
        )));
    }
    let pixels = (width * height) as usize;
    let mut levels = Vec::with_capacity(count as usize);
    for l in 0..count {
        let spacing = r.u32()?;
        if spacing != 1 << (count - 1 - l) {
            return Err(bad(format!("level {l} has spacing {spacing}")));
        }
        let residual_variance = r.f64()?;
        let appearance: Vec<[i8; APPEARANCE_DIMS]> = r.slice(pixels)?;
        let coherence: Vec<u32> = r.slice(pixels * k as usize)?;
        if let Some(c) = coherence
            .iter()
            .find(|&&c| (c & 0xffff) >= width || (c >> 16) >= height)
        {
            return Err(bad(format!(
                "level {l} has similarity-set coordinate {c:#x} outside {width}x{height}"
            )));
        }
        levels.push(LevelAnalysis {
            spacing,
            neighbourhoods: exemplar_neighbourhoods(&appearance, width, height, spacing),
            appearance,
            coherence,
            residual_variance,
        });
    }
    r.finish()?;
    Ok(ExemplarAnalysis {
        width,
        height,
        k,
        levels,
    })
}

/// [`analyze`] through `cache` (`None`: no cache, always computed). A corrupt entry is
/// recomputed and replaced with a logged warning, and the outcome says what happened.
///
/// # Errors
/// As [`analyze`] (the cache itself never fails the analysis).
pub fn analyze_cached(
    exemplar: &Exemplar,
    params: &AnalysisParams,
    cache: Option<&DiskCache>,
) -> SynthResult<(ExemplarAnalysis, CacheOutcome)> {
    let Some(cache) = cache else {
        return Ok((analyze(exemplar, params)?, CacheOutcome::Disabled));
    };
    let key = analysis_key(exemplar, params);
    let (analysis, outcome) = cache.get_or_compute(
        ANALYSIS_CACHE_KIND,
        &key,
        || analyze(exemplar, params),
        encode_analysis,
        |bytes| decode_analysis(bytes, exemplar, params),
    )?;
    if let Some(warning) = outcome.warning() {
        log::warn!(
            "exemplar analysis of {}: {warning}",
            exemplar.source.display()
        );
    }
    Ok((analysis, outcome))
}
