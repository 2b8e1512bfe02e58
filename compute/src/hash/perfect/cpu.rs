//! The sequential reference construction (Lefebvre and Hoppe 2006): buckets h1⁻¹(q) sorted by
//! decreasing size (counting sort), each given the first offset that sends all its points to
//! free slots; an occupancy bitset makes the test cheap.
//!
//! Search order, shared with the GPU construction: the candidates of bucket q are the slots s
//! for its *anchor* (its key of smallest input index), in increasing order from
//! `search_start(q)` and wrapping around; s gives the offset o = s − h0(anchor) mod |H|.
//! Occupied slots are skipped a bitset word at a time.

use super::super::error::HashError;
use super::super::keys::Universe;
use super::function::{add_mod, bucket, h0, pack_offsets, search_start, slot_coords, slot_index};
use super::sizes::PerfectSizes;
use super::table::{PerfectAttempt, PerfectConfig, PerfectHash, PerfectReport};

/// The grid points of `keys`.
///
/// # Errors
/// [`HashError::KeyOutsideUniverse`] with the largest offending key.
pub fn key_points(universe: &Universe, keys: &[u64]) -> Result<Vec<[u32; 3]>, HashError> {
    let mut bad: Option<u64> = None;
    let points = keys
        .iter()
        .map(|&k| {
            let p = if k < universe.key_count() {
                universe.point(k)
            } else {
                [u32::MAX; 3]
            };
            if !universe.contains(p) {
                bad = Some(bad.map_or(k, |b| b.max(k)));
            }
            p
        })
        .collect();
    match bad {
        Some(key) => Err(HashError::KeyOutsideUniverse {
            key,
            universe: universe.key_count(),
            description: universe.describe(),
        }),
        None => Ok(points),
    }
}

/// Keys grouped by bucket: a stable counting sort, so each bucket lists its keys in input order
/// and its anchor comes first.
pub(crate) struct Buckets {
    /// First member of each bucket, plus the total at the end.
    pub start: Vec<u32>,
    /// Key indices, bucket by bucket.
    pub members: Vec<u32>,
    /// h0 of each member, same order.
    pub h0: Vec<[u32; 3]>,
}

impl Buckets {
    fn new(sizes: &PerfectSizes, points: &[[u32; 3]]) -> Buckets {
        let nb = sizes.entries() as usize;
        let qs: Vec<u32> = points.iter().map(|&p| bucket(sizes, p)).collect();
        let mut start = vec![0u32; nb + 1];
        for &q in &qs {
            start[q as usize + 1] += 1;
        }
        for i in 0..nb {
            start[i + 1] += start[i];
        }
        let mut cursor = start.clone();
        let mut members = vec![0u32; points.len()];
        let mut hs = vec![[0u32; 3]; points.len()];
        for (i, &q) in qs.iter().enumerate() {
            let at = cursor[q as usize] as usize;
            cursor[q as usize] += 1;
            members[at] = i as u32;
            hs[at] = h0(sizes, points[i]);
        }
        Buckets {
            start,
            members,
            h0: hs,
        }
    }

    fn range(&self, q: usize) -> std::ops::Range<usize> {
        self.start[q] as usize..self.start[q + 1] as usize
    }
}

/// Checks that no two keys of a bucket share h0 (with h1 equal, (h0, h1) identifies the point).
///
/// # Errors
/// [`HashError::DuplicateKey`] with the smallest repeated key and the number of repeats.
fn check_duplicates(b: &Buckets, keys: &[u64], entries: usize) -> Result<(), HashError> {
    let mut first: Option<u64> = None;
    let mut count = 0u64;
    for q in 0..entries {
        let r = b.range(q);
        let hs = &b.h0[r.clone()];
        for j in 1..hs.len() {
            if hs[..j].contains(&hs[j]) {
                count += 1;
                let k = keys[b.members[r.start + j] as usize];
                first = Some(first.map_or(k, |f| f.min(k)));
            }
        }
    }
    match first {
        Some(key) => Err(HashError::DuplicateKey { key, count }),
        None => Ok(()),
    }
}

/// Offsets for every bucket at fixed sizes, or the bucket that found no offset.
fn place(sizes: &PerfectSizes, b: &Buckets) -> Result<Vec<u32>, (u32, usize)> {
    let nb = sizes.entries() as usize;
    let slots = sizes.slots();
    // Bucket order: decreasing size, increasing q within a size (counting sort).
    let largest = (0..nb).map(|q| b.range(q).len()).max().unwrap_or(0);
    let mut by_size = vec![0u32; largest + 2];
    for q in 0..nb {
        by_size[largest - b.range(q).len() + 1] += 1;
    }
    for i in 0..=largest {
        by_size[i + 1] += by_size[i];
    }
    let mut order = vec![0u32; nb];
    for q in 0..nb {
        let c = &mut by_size[largest - b.range(q).len()];
        order[*c as usize] = q as u32;
        *c += 1;
    }
    let mut occupied = vec![0u64; (slots as usize).div_ceil(64)];
    let is_set = |bits: &[u64], s: u32| (bits[s as usize / 64] >> (s % 64)) & 1 == 1;
    let mut offsets = vec![0u32; nb];
    for &q in &order {
        let r = b.range(q as usize);
        if r.is_empty() {
            break;
        }
        let hs = &b.h0[r];
        let anchor = hs[0];
        let s0 = search_start(q, slots);
        let mut k = 0u32;
        let mut found = None;
        'search: while k < slots {
            let mut s = s0 + k;
            if s >= slots {
                s -= slots;
            }
            let word = occupied[s as usize / 64] >> (s % 64);
            if word & 1 == 1 {
                let run = (!word).trailing_zeros().min(64 - s % 64);
                k += run.min(slots - s);
                continue;
            }
            k += 1;
            let c = slot_coords(sizes, s);
            let o: [u32; 3] = std::array::from_fn(|a| (c[a] + sizes.h - anchor[a]) % sizes.h);
            for &p in &hs[1..] {
                if is_set(&occupied, slot_index(sizes, add_mod(sizes, p, o))) {
                    continue 'search;
                }
            }
            found = Some(o);
            break;
        }
        let Some(o) = found else {
            return Err((q, hs.len()));
        };
        for &p in hs {
            let t = slot_index(sizes, add_mod(sizes, p, o));
            occupied[t as usize / 64] |= 1 << (t % 64);
        }
        offsets[q as usize] = slot_index(sizes, o);
    }
    Ok(offsets)
}

/// Builds a perfect hash of `keys` → `payloads` on the CPU, growing |Φ| until the greedy
/// assignment succeeds.
///
/// # Errors
/// Mismatched lengths, keys outside the universe, duplicate keys, a payload equal to
/// `HASH_NOT_FOUND` with unconstrained access, tables beyond the index limits, and
/// [`HashError::PerfectHashFailed`] after `max_attempts` attempts.
pub fn build_perfect_cpu(
    universe: Universe,
    keys: &[u64],
    payloads: &[u32],
    config: PerfectConfig,
) -> Result<PerfectHash, HashError> {
    super::check_inputs(keys.len(), payloads, config.access)?;
    let points = key_points(&universe, keys)?;
    let mut sizes = PerfectSizes::initial(keys.len(), &universe, config.initial_phi)?;
    let mut report = PerfectReport {
        keys: keys.len(),
        attempts: Vec::new(),
    };
    let mut checked = false;
    loop {
        let b = Buckets::new(&sizes, &points);
        if !checked {
            check_duplicates(&b, keys, sizes.entries() as usize)?;
            checked = true;
        }
        match place(&sizes, &b) {
            Ok(offsets) => {
                report.attempts.push(PerfectAttempt {
                    sizes,
                    bits_per_key: sizes.bits_per_key(keys.len()),
                    failure: None,
                });
                let words = pack_offsets(&sizes, &offsets);
                return Ok(super::fill(
                    universe,
                    sizes,
                    config.access,
                    words,
                    &points,
                    payloads,
                    report,
                ));
            }
            Err((q, size)) => {
                let reason = super::failure_reason(q, size, &sizes);
                super::next_attempt(
                    &mut report,
                    &mut sizes,
                    &universe,
                    keys.len(),
                    reason,
                    &config,
                )?;
            }
        }
    }
}
