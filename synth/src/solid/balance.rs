//! Usage balance: a per-pixel penalty on exemplar coordinates that the correction would
//! otherwise over-use, so that the volume keeps the exemplar's histogram of structures.
//!
//! **Why.** The candidates use the exemplar evenly, with about the exemplar's own luminance
//! spread, but every correction pass of the finest levels narrows what the volume uses: the
//! most used tenth of the exemplar's pixels comes to hold most of the voxels, and the
//! luminance spread and the mean gradient fall. The neighbourhood distance of a voxel whose
//! three planes only partly agree is smallest for a candidate near the average of the
//! predictions, so smooth, mid-tone pixels win and dark spots, outlines and cracks fade, the
//! more so the more passes run (counted on walnut with `bench solid`: `docs/log/solid.md`,
//! "Usage balance"; `docs/solid.md`, "Usage balance"). Kopf et al. 2007 counter the same drift
//! in texture optimization by re-weighting with the output's current histogram; here that
//! histogram is a global quantity, which a lazy synthesizer (any box, any order, the same
//! voxels) cannot read.
//!
//! **What.** A deterministic *pilot* measures the drift once per exemplar: level by level,
//! coarsest first, a fixed [`PILOT_SIDE`]³ box of that level (at [`PILOT_ORIGIN`], seed
//! [`PILOT_SEED`], the solid's default passes and jitter) is synthesized on the CPU with the
//! penalties of the coarser levels in place; how often each role's pixels are used there,
//! box-filtered over the level's `h × h` cell (coarse levels' neighbourhoods see that far;
//! widened to where an even use counts [`MIN_CELL_EXPECTED`] voxels), is compared with an
//! even use. A pixel used `q > 1` times its share gets
//! `strength · D̄ / 3 · ln q` added to its role's neighbourhood distance at that level
//! (`D̄`: the pilot's mean distance of a voxel's final triple at the level, so the penalty
//! scales with what it competes with). The penalties are static data next to the candidates:
//! every synthesizer (CPU, GPU, lazy) adds them the same way, so exactness, lazy = full and
//! any-box determinism hold. Integer arithmetic throughout (the logarithm by Mitchell's
//! approximation), so every machine computes the same penalties.

use super::analysis::SolidAnalysis;
use super::candidates::SolidCandidates;
use super::cpu::{mean_final_distance, synthesize_solid_cpu};
use super::defaults::{default_solid_jitter, default_solid_passes, DEFAULT_SOLID_PARALLEL_LEVELS};
use super::plan::VolumeBox;
use super::roles::ROLES;
use crate::coords::unpack;
use crate::{SynthParams, SynthResult};

/// Side of the pilot box at every level.
pub const PILOT_SIDE: u32 = 32;

/// Seed of the pilot's jitter.
pub const PILOT_SEED: u32 = 0x5eed_ba1a;

/// Where the pilot box lies at every level (away from the origin, which tests and first
/// looks use, so that the pilot is not the volume a user inspects).
pub const PILOT_ORIGIN: [i32; 3] = [1 << 12, 2 << 12, 3 << 12];

/// Default strength of the balance: a pixel used twice its share pays `8 · ln 2 / 3 ≈ 1.8`
/// times the pilot's mean distance in its role.
/// Measured on walnut 128² → 128³, SWD ratios x/y/z: 0 → 2.36/2.91/2.96, 4 → 1.52/1.48/1.55,
/// 8 → 1.20/1.15/1.30; docs/log/solid.md has the table on seven exemplars.
pub const DEFAULT_BALANCE: u32 = 8;

/// Fewest voxels an even use of a cell counts in the pilot: below that, chance decides
/// which pixels look over-used.
pub const MIN_CELL_EXPECTED: u64 = 32;

/// Version of the pilot's rule, part of the cache key: bumped whenever the pilot or the
/// penalty changes.
pub const PILOT_RULE: u32 = 2;

/// Largest strength accepted.
pub const MAX_BALANCE: u32 = 64;

/// Largest penalty of one pixel: keeps a distance sum of three roles inside `u32` (three
/// neighbourhood distances stay below 6·10⁷).
pub const MAX_PENALTY: u32 = 1 << 28;

/// `log2(num / den)` in 1/65536 units for `num > den > 0`, by Mitchell's approximation
/// (exact at powers of two, at most 0.086 low in between): integer only, so identical on
/// every machine.
fn log2_fixed(num: u64, den: u64) -> u64 {
    // q in 16.16 fixed point.
    let q = ((u128::from(num) << 16) / u128::from(den)) as u64;
    if q <= 1 << 16 {
        return 0;
    }
    let k = 63 - u64::from(q.leading_zeros());
    // q / 2^k − 1 in 1/65536 units, plus the integer part k − 16.
    let mantissa = if k >= 16 {
        (q - (1 << k)) >> (k - 16)
    } else {
        (q - (1 << k)) << (16 - k)
    };
    ((k - 16) << 16) + mantissa
}

/// ln 2 in 1/65536 units.
const LN2_FIXED: u64 = 45426;

/// The penalty of a pixel used `count` times where an even use is `expected_num /
/// expected_den`, at a level whose pilot mean distance is `mean_distance`.
fn penalty(
    count: u64,
    expected_num: u64,
    expected_den: u64,
    mean_distance: u64,
    strength: u32,
) -> u32 {
    // q = count · den / num; ln q = log2 q · ln 2.
    let log2 = log2_fixed(count * expected_den, expected_num);
    let ln = u128::from(log2) * u128::from(LN2_FIXED);
    let p = u128::from(strength) * u128::from(mean_distance) * ln / (3 * (1u128 << 32));
    p.min(u128::from(MAX_PENALTY)) as u32
}

/// Counts of each role's pixels in `triples`, box-filtered (wrapping) over `cell × cell`
/// pixels centred on each pixel.
fn cell_counts(triples: &[[u32; 3]], role: usize, side: u32, cell: u32) -> Vec<u64> {
    let m = side as i64;
    let mut count = vec![0u64; (side * side) as usize];
    for t in triples {
        let (x, y) = unpack(t[role]);
        count[(y * side + x) as usize] += 1;
    }
    let c = i64::from(cell.clamp(1, side));
    let half = c / 2;
    // Separable box: rows, then columns.
    let mut rows = vec![0u64; count.len()];
    for y in 0..m {
        for x in 0..m {
            rows[(y * m + x) as usize] = (0..c)
                .map(|d| count[(y * m + (x + d - half).rem_euclid(m)) as usize])
                .sum();
        }
    }
    let mut out = vec![0u64; count.len()];
    for y in 0..m {
        for x in 0..m {
            out[(y * m + x) as usize] = (0..c)
                .map(|d| rows[((y + d - half).rem_euclid(m) * m + x) as usize])
                .sum();
        }
    }
    out
}

/// Fills `candidates.balance` for `analysis` with `strength` (0: no penalties, the field
/// left empty). Runs the pilot described in the module docs on the CPU; `on_level` is called
/// after each level's pilot (tens of seconds in all at 128² on 2 cores).
///
/// # Errors
/// Parameters that do not fit the analysis (none for candidates made from it).
pub fn balance_usage(
    analysis: &SolidAnalysis,
    candidates: &mut SolidCandidates,
    strength: u32,
    on_level: &mut dyn FnMut(u32),
) -> SynthResult<()> {
    balance_finest_levels(analysis, candidates, strength, None, on_level)
}

/// [`balance_usage`] on the `finest` finest levels only (`None`: every level); the coarser
/// levels keep no penalty and run no pilot. On slate, a fine grain whose coarser stack levels
/// hold little structure, the penalties of the coarser levels are what make its slices too
/// contrasted at 2–4 pixels (`docs/solid.md`, "The balance's levels"); on most exemplars they
/// are what keeps the structures.
///
/// # Errors
/// As [`balance_usage`].
pub fn balance_finest_levels(
    analysis: &SolidAnalysis,
    candidates: &mut SolidCandidates,
    strength: u32,
    finest: Option<u32>,
    on_level: &mut dyn FnMut(u32),
) -> SynthResult<()> {
    candidates.balance.clear();
    if strength == 0 {
        return Ok(());
    }
    let levels = analysis.levels.len();
    let m = analysis.side;
    let passes = default_solid_passes(levels as u32);
    let jitter = default_solid_jitter(levels as u32);
    let zeros = || -> [Vec<u32>; ROLES] { std::array::from_fn(|_| vec![0; (m * m) as usize]) };
    candidates.balance = (0..levels).map(|_| zeros()).collect();
    let window = VolumeBox {
        origin: PILOT_ORIGIN,
        size: [PILOT_SIDE; 3],
    };
    for l in 0..levels {
        if finest.is_some_and(|k| l + (k as usize) < levels) {
            on_level(l as u32);
            continue;
        }
        // The pyramid down to level l, which the synthesizer then treats as its finest.
        // Only the levels kept are copied (at 256² a level's candidates are tens of MB).
        let a = SolidAnalysis {
            side: analysis.side,
            role_image: analysis.role_image,
            levels: analysis.levels[..=l].to_vec(),
        };
        let c = SolidCandidates {
            levels: candidates.levels[..=l].to_vec(),
            reports: candidates.reports[..=l].to_vec(),
            balance: candidates.balance[..=l].to_vec(),
        };
        // Level l runs as it does in the full pyramid: parallel only if it is one of the
        // default parallel levels there.
        let first_parallel = levels.saturating_sub(DEFAULT_SOLID_PARALLEL_LEVELS as usize);
        let params = SynthParams::new(l as u32 + 1, PILOT_SEED, &passes[..=l], &jitter[..=l])?
            .with_parallel_levels((l + 1).saturating_sub(first_parallel) as u32)?;
        let pilot = synthesize_solid_cpu(&a, &c, &params, window)?;
        let finest = pilot.levels.last().expect("a finest level");
        let mean_distance = mean_final_distance(&a, &c, l as u32, finest);
        let triples = pilot.window_triples();
        // The level's cell, widened until an even use counts MIN_CELL_EXPECTED voxels: a
        // cell of one pixel at the finest level expects 2 voxels (32³ voxels over 128²
        // pixels), and chance counts of 4–6 would read as over-use.
        let mut cell = analysis.levels[l].spacing;
        while (triples.len() as u64) * u64::from(cell * cell) < MIN_CELL_EXPECTED * u64::from(m * m)
            && cell < m
        {
            cell *= 2;
        }
        // Even use of a cell: voxels · cell² / m².
        let expected_num = triples.len() as u64 * u64::from(cell * cell);
        let expected_den = u64::from(m * m);
        let balance: [Vec<u32>; ROLES] = std::array::from_fn(|r| {
            cell_counts(&triples, r, m, cell)
                .into_iter()
                .map(|n| penalty(n, expected_num, expected_den, mean_distance, strength))
                .collect()
        });
        candidates.balance[l] = balance;
        on_level(l as u32);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mitchell_log_is_exact_at_powers_of_two_and_close_between() {
        assert_eq!(log2_fixed(1, 1), 0);
        assert_eq!(log2_fixed(1, 2), 0);
        assert_eq!(log2_fixed(2, 1), 1 << 16);
        assert_eq!(log2_fixed(8, 1), 3 << 16);
        assert_eq!(log2_fixed(3, 4), 0);
        for (n, d) in [(3u64, 1u64), (5, 2), (7, 3), (1000, 7), (101, 100)] {
            let exact = (n as f64 / d as f64).log2();
            let got = log2_fixed(n, d) as f64 / 65536.0;
            assert!(
                got <= exact + 1e-4 && exact - got < 0.087,
                "{n}/{d}: {got} vs {exact}"
            );
        }
    }

    #[test]
    fn cell_counts_sum_every_pixel_cell_squared_times() {
        let triples: Vec<[u32; 3]> = (0..40u32)
            .map(|i| [i % 16, ((i * 7) % 16) | (3 << 16), 0])
            .collect();
        for cell in [1, 2, 4] {
            let c = cell_counts(&triples, 1, 16, cell);
            assert_eq!(c.iter().sum::<u64>(), 40 * u64::from(cell * cell));
        }
    }

    #[test]
    fn penalties_grow_with_overuse_and_are_zero_below_an_even_share() {
        assert_eq!(penalty(1, 2, 1, 1000, 8), 0);
        assert_eq!(penalty(2, 2, 1, 1000, 8), 0);
        let twice = penalty(4, 2, 1, 30_000, 8);
        let four = penalty(8, 2, 1, 30_000, 8);
        // 8 · ln 2 · 30000 / 3 ≈ 55452.
        assert!((55400..=55460).contains(&twice), "{twice}");
        assert!(four.abs_diff(2 * twice) <= 1, "{four} vs {twice}");
        assert_eq!(
            penalty(u64::MAX >> 20, 1, 1, u64::MAX >> 8, 64),
            MAX_PENALTY
        );
    }
}
