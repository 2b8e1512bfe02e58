//! Keys of lazy synthesis: one `u64` per voxel of a level, the Morton code of its absolute
//! position shifted into the unsigned range, with the low bits left free for a stage number.
//!
//! Sorting the stage-tagged keys puts the voxels in Morton order, the order the GPU radix sort
//! and the dependency sets use; the stage, stored as `STAGE_MAX − stage`, sorts the largest
//! stage of a voxel first, so that a unique pass over sorted keys keeps the latest stage a
//! voxel is needed at.

use crate::{SynthError, SynthResult};
use lazysolid_compute::hash::{morton_decode, morton_encode};

pub use crate::shader_constants::LAZY_AXIS_BITS;

/// Added to every coordinate so that positions `−LAZY_BIAS..LAZY_BIAS` map onto
/// `0..2^LAZY_AXIS_BITS`.
pub const LAZY_BIAS: i32 = 1 << (LAZY_AXIS_BITS - 1);

/// Low bits of a tagged key that hold the stage.
pub const STAGE_BITS: u32 = 64 - 3 * LAZY_AXIS_BITS;

/// Largest stage a tag holds: 8 subpasses times the largest pass count, plus the upsampling.
pub const STAGE_MAX: u32 = (1 << STAGE_BITS) - 1;

/// Largest coordinate magnitude of a requested finest-level voxel: the dependencies reach a
/// few voxels beyond the request per pass and level, and must stay inside the key range.
pub const MAX_LAZY_COORD: i32 = LAZY_BIAS - 4096;

/// The key of absolute position `p` (which must lie within ±[`LAZY_BIAS`]).
pub fn lazy_key(p: [i32; 3]) -> u64 {
    morton_encode(p.map(|v| (v + LAZY_BIAS) as u32), 3)
}

/// The absolute position of key `k`.
pub fn lazy_position(k: u64) -> [i32; 3] {
    morton_decode(k, 3).map(|v| v as i32 - LAZY_BIAS)
}

/// Key `k` with stage `stage` in its low bits (largest stage sorting first).
pub fn tag(k: u64, stage: u32) -> u64 {
    k << STAGE_BITS | (STAGE_MAX - stage) as u64
}

/// The key and the stage of tagged key `t`.
pub fn untag(t: u64) -> (u64, u32) {
    (t >> STAGE_BITS, STAGE_MAX - (t & STAGE_MAX as u64) as u32)
}

/// Checks that finest-level position `p` may be requested.
///
/// # Errors
/// [`SynthError::Parameter`] naming the coordinate and the limit.
pub fn check_request(p: [i32; 3]) -> SynthResult<()> {
    check_within(
        p,
        -MAX_LAZY_COORD..MAX_LAZY_COORD + 1,
        &format!("each coordinate must lie in -{MAX_LAZY_COORD}..={MAX_LAZY_COORD}"),
    )
}

/// Checks that every coordinate of requested position `p` lies in `range`; the error names
/// the coordinate and says `limit`.
pub(crate) fn check_within(
    p: [i32; 3],
    range: std::ops::Range<i32>,
    limit: &str,
) -> SynthResult<()> {
    match (0..3).find(|&a| !range.contains(&p[a])) {
        Some(a) => Err(SynthError::Parameter {
            name: [
                "requested voxel x",
                "requested voxel y",
                "requested voxel z",
            ][a],
            value: p[a].to_string(),
            limit: limit.to_string(),
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_round_trip_and_sort_like_morton_order() {
        for p in [[0, 0, 0], [-1, 5, -7], [MAX_LAZY_COORD, -MAX_LAZY_COORD, 3]] {
            assert_eq!(lazy_position(lazy_key(p)), p);
            for stage in [0, 1, 17, STAGE_MAX] {
                assert_eq!(untag(tag(lazy_key(p), stage)), (lazy_key(p), stage));
            }
        }
        let k = lazy_key([3, 4, 5]);
        assert!(tag(k, 9) < tag(k, 2), "the larger stage sorts first");
        assert!(tag(k, 0) < tag(k + 1, STAGE_MAX));
        assert!(check_request([0, MAX_LAZY_COORD + 1, 0]).is_err());
    }
}
