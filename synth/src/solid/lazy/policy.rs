//! What a lazy state keeps between requests (`docs/lazy.md`, "Memory policies").
//!
//! Every version is a function of absolute positions only, so dropping any of them never
//! changes a result: a later request that needs a dropped version recomputes it, bit for bit.
//! The policies differ in memory and in what a later request recomputes.
//!
//! - **keep**: every version of every voxel stays; nothing is ever computed twice.
//! - **budget** (`N MB`): after each chunk of a request, levels are kept in the order a later
//!   request reads them while their bytes together stay within `N` MB: from the coarsest down
//!   to the second finest, then the finest. The first level past the budget keeps the part of
//!   its voxels that the rest of the budget holds, a region (the first voxels in Morton order),
//!   and every level after it in that order is emptied. The coarse levels, small and shared by
//!   every later cut, stay first. The finest level comes last because no later request of new
//!   voxels reads it in bulk: a new voxel's finest versions are corrected from its own
//!   neighbours, which are new too except along the rim where a cap meets what was requested
//!   before, while the second finest level's versions are the parents of every new finest
//!   voxel and most of a cut's second-finest neighbourhood was computed by the surface before
//!   it (`docs/lazy.md`, "Which level a cut recomputes"). Keeping part of a level rather than
//!   none of it makes the recomputation grow with what the budget lacks instead of jumping
//!   when a level no longer fits. Requests run in Morton-ordered chunks of at most
//!   [`LAZY_CHUNK_VOXELS`] voxels, so the state alive during a request is the kept levels plus
//!   one chunk's other levels instead of the whole surface's.

use crate::{SynthError, SynthResult};
use std::fmt;
use std::str::FromStr;

/// Requested voxels synthesized together before the policy applies (the last chunk may be
/// smaller): about 1/5 of the armadillo's interpolation voxels at 1024³.
pub const LAZY_CHUNK_VOXELS: usize = 1 << 20;

/// The default byte budget of the kept state, in MB (10⁶ bytes): with the armadillo's TileTree
/// at 1024³ (11.85 MB) the state and its store stay within 64 MB, and at 256³ it holds every
/// level but the finest of the armadillo's surface (`docs/lazy.md`, "Memory policies").
pub const DEFAULT_STATE_BUDGET_MB: u64 = 48;

/// What a lazy state keeps between requests (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MemoryPolicy {
    /// Every version of every voxel.
    Keep,
    /// Levels, in the order the module docs give, within this many bytes.
    Budget(u64),
}

impl Default for MemoryPolicy {
    fn default() -> MemoryPolicy {
        MemoryPolicy::Budget(DEFAULT_STATE_BUDGET_MB * 1_000_000)
    }
}

impl MemoryPolicy {
    /// What to keep of each level, given each level's bytes (coarsest first). The budget
    /// fills in the order the module docs give, coarsest to second finest, then the finest;
    /// the first level past it keeps what the rest of the budget holds.
    pub fn plan(&self, level_bytes: &[u64]) -> Vec<LevelKeep> {
        let n = level_bytes.len();
        let mut plan = vec![LevelKeep::Nothing; n];
        match *self {
            MemoryPolicy::Keep => plan.fill(LevelKeep::All),
            MemoryPolicy::Budget(budget) => {
                let order = (0..n.saturating_sub(1)).chain(n.checked_sub(1));
                let mut sum = 0u64;
                for l in order {
                    if sum + level_bytes[l] > budget {
                        if sum < budget {
                            plan[l] = LevelKeep::Part(budget - sum);
                        }
                        break;
                    }
                    sum += level_bytes[l];
                    plan[l] = LevelKeep::All;
                }
            }
        }
        plan
    }
}

/// What a memory policy keeps of one level of the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelKeep {
    /// Every voxel.
    All,
    /// The voxels that fit in this many bytes, tables and versions together.
    Part(u64),
    /// No voxel.
    Nothing,
}

impl fmt::Display for MemoryPolicy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MemoryPolicy::Keep => write!(f, "keep"),
            MemoryPolicy::Budget(b) if b % 1_000_000 == 0 => write!(f, "{}MB", b / 1_000_000),
            MemoryPolicy::Budget(b) => write!(f, "{b}B"),
        }
    }
}

impl FromStr for MemoryPolicy {
    type Err = SynthError;

    /// `keep`, or a budget: a whole number of `MB` (10⁶ bytes), e.g. `32MB`.
    fn from_str(s: &str) -> SynthResult<MemoryPolicy> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("keep") {
            return Ok(MemoryPolicy::Keep);
        }
        let bad = || SynthError::Parameter {
            name: "memory policy",
            value: format!("{s:?}"),
            limit: "\"keep\" or a budget in whole MB from 1 to 1000000, e.g. \"32MB\"".into(),
        };
        let digits = t
            .strip_suffix("MB")
            .or_else(|| t.strip_suffix("mb"))
            .ok_or_else(bad)?
            .trim();
        let mb: u64 = digits.parse().map_err(|_| bad())?;
        if !(1..=1_000_000).contains(&mb) {
            return Err(bad());
        }
        Ok(MemoryPolicy::Budget(mb * 1_000_000))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn policies_parse_print_and_choose_levels() {
        assert_eq!("keep".parse::<MemoryPolicy>().unwrap(), MemoryPolicy::Keep);
        let b: MemoryPolicy = "32MB".parse().unwrap();
        assert_eq!(b, MemoryPolicy::Budget(32_000_000));
        assert_eq!(b.to_string(), "32MB");
        assert_eq!(
            MemoryPolicy::default(),
            MemoryPolicy::Budget(DEFAULT_STATE_BUDGET_MB * 1_000_000)
        );
        for bad in ["", "32", "0MB", "-3MB", "1.5MB", "lots", "2000000MB"] {
            let e = bad.parse::<MemoryPolicy>().unwrap_err().to_string();
            assert!(
                e.contains("memory policy") && e.contains("keep"),
                "{bad}: {e}"
            );
        }
        use LevelKeep::{All, Nothing, Part};
        let bytes = [1_000_000, 3_000_000, 20_000_000, 90_000_000];
        let plan = |p: MemoryPolicy| p.plan(&bytes);
        assert_eq!(plan(MemoryPolicy::Keep), [All; 4]);
        let budget = MemoryPolicy::Budget;
        assert_eq!(plan(budget(114_000_000)), [All; 4]);
        assert_eq!(plan(budget(113_999_999)), [All, All, All, Part(89_999_999)]);
        assert_eq!(plan(budget(24_000_000)), [All, All, All, Nothing]);
        assert_eq!(
            plan(budget(23_999_999)),
            [All, All, Part(19_999_999), Nothing]
        );
        assert_eq!(plan(budget(100)), [Part(100), Nothing, Nothing, Nothing]);
        // The finest level goes last: while the second finest does not fit whole, the finest
        // is emptied however small it is; it is kept, whole or in part, after the others.
        let fine = [1_000_000, 3_000_000, 20_000_000, 2_000_000];
        assert_eq!(
            budget(10_000_000).plan(&fine),
            [All, All, Part(6_000_000), Nothing]
        );
        assert_eq!(budget(26_000_000).plan(&fine), [All; 4]);
        assert_eq!(
            budget(25_000_000).plan(&fine),
            [All, All, All, Part(1_000_000)]
        );
        assert_eq!(budget(24_000_000).plan(&fine), [All, All, All, Nothing]);
        assert_eq!(budget(1).plan(&[]), Vec::<LevelKeep>::new());
        assert_eq!(budget(5).plan(&[4]), [All]);
        assert_eq!(budget(5).plan(&[0, 9]), [All, Part(5)]);
    }
}
