//! Perfect spatial hashing (Lefebvre and Hoppe 2006): h(p) = h0(p) + Φ[h1(p)] mod |H| with
//! h0(p) = p mod |H| and h1(p) = p mod |Φ| per axis, in 2D and 3D. A lookup is two reads (one
//! offset, one payload); the offset table costs about 4 bits per key.
//!
//! - [`sizes`](PerfectSizes): |H| the smallest extent with |H|^d ≥ |K|, |Φ| started at
//!   σ = 1/(2d) entries per key and grown by 10 % per failure, coprime with |H|;
//! - [`build_perfect_cpu`]: the sequential greedy reference;
//! - [`PerfectBuilder`]: the parallel construction in Vulkan compute;
//! - [`PerfectConstruction`]: which of the two builds a table (by default the faster one on
//!   the device: the CPU build on a CPU driver);
//! - [`PerfectHashGpu`]: a table on the device, read by `glsl/include/hash/perfect.glsl`;
//! - [`BlockedPerfectHash`]: blocks of texels with duplicated borders so that one block
//!   serves a whole trilinear footprint.
//!
//! Layout, sizes and measurements: `docs/hashing.md`, "Perfect spatial hashing". Perfect
//! spatial hashing is the subject of US patent 7,619,623 (see the README).

pub(crate) mod blocked;
mod construction;
mod cpu;
mod function;
pub(crate) mod gpu;
mod kernels;
mod sizes;
mod table;

pub use blocked::{
    block_keys, blocked_sizes, BlockChoice, BlockedLayout, BlockedPerfectHash, BLOCK_SIZES,
};
pub use construction::PerfectConstruction;
pub use cpu::{build_perfect_cpu, key_points};
pub use function::{
    bucket, h0, pack_offsets, read_offset, search_start, slot, slot_coords, slot_index,
};
pub use gpu::{PerfectBuilder, PerfectHashGpu, PerfectParams};
pub use kernels::PerfectKernels;
pub use sizes::{gcd, initial_sigma, PerfectSizes, GROWTH};
pub use table::{
    table_bytes, PerfectAccess, PerfectAttempt, PerfectConfig, PerfectHash, PerfectReport,
};

use super::error::HashError;
use super::keys::Universe;
use crate::shader_constants::HASH_NOT_FOUND;

/// Checks lengths and, for unconstrained access, that no payload is `HASH_NOT_FOUND` (the
/// answer for absent keys).
fn check_inputs(n: usize, payloads: &[u32], access: PerfectAccess) -> Result<(), HashError> {
    if n != payloads.len() {
        return Err(HashError::InvalidArgument(format!(
            "{n} keys but {} payloads",
            payloads.len()
        )));
    }
    if access == PerfectAccess::Unconstrained {
        if let Some(&p) = payloads.iter().find(|&&p| p == HASH_NOT_FOUND) {
            return Err(not_found_payload(p));
        }
    }
    Ok(())
}

fn not_found_payload(payload: u32) -> HashError {
    HashError::PayloadTooLarge {
        payload,
        format: "an unconstrained perfect hash (HASH_NOT_FOUND marks absent keys)".into(),
        bits: 32,
        max: HASH_NOT_FOUND - 1,
    }
}

fn failure_reason(q: u32, size: usize, sizes: &PerfectSizes) -> String {
    format!(
        "bucket {q} ({size} key(s)) found no offset placing all its keys in free slots among the {} slots",
        sizes.slots()
    )
}

/// Records a failed attempt and moves to grown sizes, or fails after `max_attempts`.
fn next_attempt(
    report: &mut PerfectReport,
    sizes: &mut PerfectSizes,
    universe: &Universe,
    n: usize,
    reason: String,
    config: &PerfectConfig,
) -> Result<(), HashError> {
    report.attempts.push(PerfectAttempt {
        sizes: *sizes,
        bits_per_key: sizes.bits_per_key(n),
        failure: Some(reason.clone()),
    });
    if report.attempts.len() as u32 >= config.max_attempts {
        return Err(HashError::PerfectHashFailed {
            attempts: report.attempts.len() as u32,
            sizes: sizes.describe(),
            reason,
        });
    }
    *sizes = sizes.grown(universe)?;
    Ok(())
}

/// Writes the payloads (and tags) of a finished offset table on the host.
fn fill(
    universe: Universe,
    sizes: PerfectSizes,
    access: PerfectAccess,
    offsets: Vec<u32>,
    points: &[[u32; 3]],
    payloads: &[u32],
    report: PerfectReport,
) -> PerfectHash {
    let slots = sizes.slots() as usize;
    let mut data = vec![0u32; slots];
    let mut tags = (access == PerfectAccess::Unconstrained).then(|| vec![0u32; slots]);
    for (p, &payload) in points.iter().zip(payloads) {
        let s = slot(&sizes, &offsets, *p) as usize;
        data[s] = payload;
        if let Some(t) = tags.as_mut() {
            t[s] = bucket(&sizes, *p) + 1;
        }
    }
    PerfectHash {
        universe,
        sizes,
        access,
        offsets,
        data,
        tags,
        report,
    }
}
