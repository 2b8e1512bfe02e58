//! What a lazy state keeps between requests (`docs/lazy.md`, "Memory policies").
//!
//! Every version is a function of absolute positions only, so dropping any of them never
//! changes a result: a later request that needs a dropped version recomputes it, bit for bit.
//! The policies differ in memory and in what a later request recomputes.
//!
//! - **keep**: every version of every voxel stays; nothing is ever computed twice.
//! - **budget** (`N MB`): after each chunk of a request, levels are kept from the coarsest down
//!   while their bytes together stay within `N` MB; the first level past the budget and every
//!   finer one are emptied. The coarse levels, small and shared by every later cut, stay; the
//!   fine levels, most of the bytes and local to the surface just requested, are recomputed
//!   where a later request reaches them. Requests run in Morton-ordered chunks of at most
//!   [`LAZY_CHUNK_VOXELS`] voxels, so the state alive during a request is the kept levels plus
//!   one chunk's fine levels instead of the whole surface's.

use crate::{SynthError, SynthResult};
use std::fmt;
use std::str::FromStr;

/// Requested voxels synthesized together before the policy applies (the last chunk may be
/// smaller): about 1/5 of the armadillo's interpolation voxels at 1024³.
pub const LAZY_CHUNK_VOXELS: usize = 1 << 20;

/// The default byte budget of the kept state, in MB (10⁶ bytes).
pub const DEFAULT_STATE_BUDGET_MB: u64 = 32;

/// What a lazy state keeps between requests (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MemoryPolicy {
    /// Every version of every voxel.
    Keep,
    /// Whole levels, coarsest first, within this many bytes.
    Budget(u64),
}

impl Default for MemoryPolicy {
    fn default() -> MemoryPolicy {
        MemoryPolicy::Budget(DEFAULT_STATE_BUDGET_MB * 1_000_000)
    }
}

impl MemoryPolicy {
    /// How many levels (coarsest first) to keep, given each level's bytes.
    pub fn levels_kept(&self, level_bytes: &[u64]) -> usize {
        match *self {
            MemoryPolicy::Keep => level_bytes.len(),
            MemoryPolicy::Budget(budget) => {
                let mut sum = 0u64;
                level_bytes
                    .iter()
                    .take_while(|&&b| {
                        sum += b;
                        sum <= budget
                    })
                    .count()
            }
        }
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
        assert_eq!(MemoryPolicy::default(), b);
        for bad in ["", "32", "0MB", "-3MB", "1.5MB", "lots", "2000000MB"] {
            let e = bad.parse::<MemoryPolicy>().unwrap_err().to_string();
            assert!(
                e.contains("memory policy") && e.contains("keep"),
                "{bad}: {e}"
            );
        }
        let bytes = [1_000_000, 3_000_000, 20_000_000, 90_000_000];
        assert_eq!(MemoryPolicy::Keep.levels_kept(&bytes), 4);
        assert_eq!(MemoryPolicy::Budget(24_000_000).levels_kept(&bytes), 3);
        assert_eq!(MemoryPolicy::Budget(23_999_999).levels_kept(&bytes), 2);
        assert_eq!(MemoryPolicy::Budget(100).levels_kept(&bytes), 0);
    }
}
