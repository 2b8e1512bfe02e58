//! The solid candidates through the on-disk cache (`synth/cache.rs`): the precompute is the
//! slow part of a solid synthesis (tens of seconds for a 64² exemplar on lavapipe) and a pure
//! function of the role images and the candidate parameters, so a second run of the same
//! exemplars reads it back bit-identical instead.
//!
//! The key holds every role's pixels (and which images are shared, since that decides nothing
//! but is cheap to include), the candidate parameters and the constants of the candidate code;
//! the payload holds per level each role's sets and the level's coherence report.

use super::balance::MAX_PENALTY;
use super::candidates::{
    CandidateParams, CandidateSets, LevelReport, SolidCandidates, KEPT, MAX_CANDIDATES,
    MAX_COHERENCE_ITERATIONS,
};
use super::roles::{SolidExemplars, ROLES};
use crate::analysis_cache::ANALYSIS_FORMAT_VERSION;
use crate::cache::{
    ByteReader, ByteWriter, CacheError, CacheKey, CacheOutcome, DiskCache, KeyBuilder,
};
use crate::error::SynthResult;

/// Cache kind (the entries' subfolder) of solid candidates.
pub const CANDIDATES_CACHE_KIND: &str = "solid-candidates";

/// Version of the candidate construction and its payload: bumped whenever the strips, the
/// crossbar ranking, the coherence filter, the usage balance or the encoding change (2: the
/// balance's penalties after the levels; 3: the balance's pilot corrects the finest level in
/// a parallel pass, as the synthesizer now does).
pub const CANDIDATES_FORMAT_VERSION: u32 = 3;

/// The cache key of the candidates of `exemplars` with `params`.
pub fn candidates_key(exemplars: &SolidExemplars, params: &CandidateParams) -> CacheKey {
    let mut b = KeyBuilder::new(CANDIDATES_CACHE_KIND, CANDIDATES_FORMAT_VERSION)
        .u32("stack version", ANALYSIS_FORMAT_VERSION);
    for r in 0..ROLES {
        let image = exemplars.role(r);
        b = b
            .u32("role image", exemplars.role_image[r] as u32)
            .u32("width", image.width)
            .u32("height", image.height)
            .bytes("rgb", image.rgb.as_flattened());
    }
    b.u32("feature weight", exemplars.feature_weight)
        .u32("feature rule", crate::feature::FEATURE_RULE)
        .u32("feature mask", exemplars.feature_mask.code())
        .u32("strip", params.strip)
        .u32("s", params.s)
        .bool("coherence", params.coherence)
        .u32("balance", params.balance)
        .u32("balance levels", params.balance_levels.unwrap_or(u32::MAX))
        .u32("pilot side", super::balance::PILOT_SIDE)
        .u32("pilot seed", super::balance::PILOT_SEED)
        .u32("pilot rule", super::balance::PILOT_RULE)
        .u32("kept", KEPT as u32)
        .u32("max candidates", MAX_CANDIDATES as u32)
        .u32("max iterations", MAX_COHERENCE_ITERATIONS)
        .finish()
}

/// Encodes `candidates` as a cache payload.
pub fn encode_candidates(candidates: &SolidCandidates) -> Vec<u8> {
    let mut w = ByteWriter::default();
    w.u32(candidates.levels.len() as u32);
    for (sets, report) in candidates.levels.iter().zip(&candidates.reports) {
        for set in sets {
            w.u32(set.slots as u32);
            w.u32(set.counts.len() as u32);
            w.slice(&set.counts);
            w.slice(&set.errors);
            w.slice(&set.triples);
        }
        w.u32(report.iterations);
        w.u64(report.fallbacks);
        w.u64(report.cut);
        w.u64(report.candidates);
    }
    w.u32(candidates.balance.len() as u32);
    for level in &candidates.balance {
        for role in level {
            w.slice(role);
        }
    }
    w.into_bytes()
}

/// Decodes a payload of [`encode_candidates`] for exemplars of side `side`, checking every
/// size, count and coordinate, so that a payload that passed the checksum but does not belong
/// here is refused rather than handed to a synthesizer.
///
/// # Errors
/// [`CacheError::Decode`] naming the first field that does not fit.
pub fn decode_candidates(bytes: &[u8], side: u32) -> Result<SolidCandidates, CacheError> {
    let bad = |what: String| CacheError::Decode(what);
    let mut r = ByteReader::new(bytes);
    let count = r.u32()?;
    if count != side.ilog2() + 1 {
        return Err(bad(format!(
            "{count} levels, exemplars of side {side} have {}",
            side.ilog2() + 1
        )));
    }
    let pixels = (side * side) as usize;
    let mut levels = Vec::with_capacity(count as usize);
    let mut reports = Vec::with_capacity(count as usize);
    for l in 0..count {
        let mut sets = Vec::with_capacity(ROLES);
        for role in 0..ROLES {
            let (slots, n) = (r.u32()? as usize, r.u32()? as usize);
            if slots != MAX_CANDIDATES || n != pixels {
                return Err(bad(format!(
                    "level {l} role {role}: {n} pixels of {slots} slots, expected {pixels} of {MAX_CANDIDATES}"
                )));
            }
            let counts: Vec<u32> = r.slice(n)?;
            let errors: Vec<u32> = r.slice(n * slots)?;
            let triples: Vec<[u32; 3]> = r.slice(n * slots)?;
            if let Some(c) = counts.iter().find(|&&c| c == 0 || c as usize > slots) {
                return Err(bad(format!(
                    "level {l} role {role}: a set of {c} candidates"
                )));
            }
            if let Some(t) = triples
                .iter()
                .flatten()
                .find(|&&c| (c & 0xffff) >= side || (c >> 16) >= side)
            {
                return Err(bad(format!(
                    "level {l} role {role}: coordinate {t:#x} outside {side}x{side}"
                )));
            }
            sets.push(CandidateSets {
                slots,
                triples,
                errors,
                counts,
            });
        }
        levels.push(sets.try_into().expect("three roles"));
        reports.push(LevelReport {
            iterations: r.u32()?,
            fallbacks: r.u64()?,
            cut: r.u64()?,
            candidates: r.u64()?,
        });
    }
    let balanced = r.u32()?;
    if balanced != 0 && balanced != count {
        return Err(bad(format!(
            "penalties of {balanced} levels, the candidates have {count}"
        )));
    }
    let mut balance = Vec::with_capacity(balanced as usize);
    for l in 0..balanced {
        let mut roles = Vec::with_capacity(ROLES);
        for role in 0..ROLES {
            let penalties: Vec<u32> = r.slice(pixels)?;
            if let Some(p) = penalties.iter().find(|&&p| p > MAX_PENALTY) {
                return Err(bad(format!(
                    "level {l} role {role}: penalty {p} above {MAX_PENALTY}"
                )));
            }
            roles.push(penalties);
        }
        balance.push(roles.try_into().expect("three roles"));
    }
    r.finish()?;
    Ok(SolidCandidates {
        levels,
        reports,
        balance,
    })
}

/// `compute()`'s candidates of `exemplars` with `params`, through `cache` (`None`: always
/// computed). A corrupt entry is recomputed and replaced with a logged warning, and the
/// outcome says what happened.
///
/// # Errors
/// `compute`'s (the cache itself never fails the precompute).
pub fn candidates_cached(
    exemplars: &SolidExemplars,
    params: &CandidateParams,
    cache: Option<&DiskCache>,
    compute: impl FnOnce() -> SynthResult<SolidCandidates>,
) -> SynthResult<(SolidCandidates, CacheOutcome)> {
    let Some(cache) = cache else {
        return Ok((compute()?, CacheOutcome::Disabled));
    };
    let key = candidates_key(exemplars, params);
    let side = exemplars.side();
    let (candidates, outcome) = cache.get_or_compute(
        CANDIDATES_CACHE_KIND,
        &key,
        compute,
        encode_candidates,
        |bytes| decode_candidates(bytes, side),
    )?;
    if let Some(warning) = outcome.warning() {
        log::warn!(
            "solid candidates of {}: {warning}",
            exemplars.role(0).source.display()
        );
    }
    Ok((candidates, outcome))
}
