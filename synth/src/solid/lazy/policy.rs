//! What a lazy state keeps between requests (`docs/lazy.md`, "Memory policies").
//!
//! Every version is a function of absolute positions only, so dropping any of them never
//! changes a result: a later request that needs a dropped version recomputes it, bit for bit.
//! The policies differ in memory and in what a later request recomputes.
//!
//! - **keep**: every version of every voxel stays; nothing is ever computed twice.
//! - **budget** (`N MB`): after each chunk of a request, levels are kept in the order a later
//!   request reads them while their bytes together stay within `N` MB: from the coarsest down
//!   to the second finest, then the finest; the first level past the budget and every level
//!   after it in that order are emptied. The coarse levels, small and shared by every later
//!   cut, stay first. The finest level comes last because no later request of new voxels reads
//!   it in bulk: a new voxel's finest versions are corrected from its own neighbours, which are
//!   new too except along the rim where a cap meets what was requested before, while the
//!   second finest level's versions are the parents of every new finest voxel and most of a
//!   cut's second-finest neighbourhood was computed by the surface before it (`docs/lazy.md`,
//!   "Which level a cut recomputes"). Requests run in Morton-ordered chunks of at most
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
    /// Whole levels, in the order the module docs give, within this many bytes.
    Budget(u64),
}

impl Default for MemoryPolicy {
    fn default() -> MemoryPolicy {
        MemoryPolicy::Budget(DEFAULT_STATE_BUDGET_MB * 1_000_000)
    }
}

impl MemoryPolicy {
    /// Which levels to keep, given each level's bytes (coarsest first): `true` for a kept
    /// level. The budget fills in the order the module docs give, coarsest to second finest,
    /// then the finest, and stops at the first level past it.
    pub fn levels_kept(&self, level_bytes: &[u64]) -> Vec<bool> {
        let n = level_bytes.len();
        let mut kept = vec![false; n];
        match *self {
            MemoryPolicy::Keep => kept.fill(true),
            MemoryPolicy::Budget(budget) => {
                let order = (0..n.saturating_sub(1)).chain(n.checked_sub(1));
                let mut sum = 0u64;
                for l in order {
                    sum += level_bytes[l];
                    if sum > budget {
                        break;
                    }
                    kept[l] = true;
                }
            }
        }
        kept
    }
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
        let bytes = [1_000_000, 3_000_000, 20_000_000, 90_000_000];
        let kept = |p: MemoryPolicy| p.levels_kept(&bytes);
        assert_eq!(kept(MemoryPolicy::Keep), [true; 4]);
        let budget = MemoryPolicy::Budget;
        assert_eq!(kept(budget(114_000_000)), [true; 4]);
        assert_eq!(kept(budget(113_999_999)), [true, true, true, false]);
        assert_eq!(kept(budget(24_000_000)), [true, true, true, false]);
        assert_eq!(kept(budget(23_999_999)), [true, true, false, false]);
        assert_eq!(kept(budget(100)), [false; 4]);
        // The finest level goes last: a small finest level is still dropped when the second
        // finest does not fit, and kept after it when it does.
        let fine = [1_000_000, 3_000_000, 20_000_000, 2_000_000];
        assert_eq!(
            budget(10_000_000).levels_kept(&fine),
            [true, true, false, false]
        );
        assert_eq!(budget(26_000_000).levels_kept(&fine), [true; 4]);
        assert_eq!(
            budget(25_000_000).levels_kept(&fine),
            [true, true, true, false]
        );
        assert_eq!(budget(1).levels_kept(&[]), Vec::<bool>::new());
        assert_eq!(budget(5).levels_kept(&[4]), [true]);
    }
}
