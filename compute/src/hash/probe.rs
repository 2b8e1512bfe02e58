//! Probe sequences of the Robin Hood tables; must match `glsl/include/hash/probe.glsl`.

use crate::shader_constants::{COHERENT_OFFSETS, HASH_PROBE_COHERENT, HASH_PROBE_RANDOM};

/// Which slots a key visits, step after step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Probe {
    /// h_a(k) = (k + o_(a−1)) mod |H|: the whole table is translated at each step, so
    /// neighbouring keys probe neighbouring cells (García et al. 2011).
    Coherent,
    /// h_a(k) = mix(16k + a) mod |H|: an unrelated slot at each step (h_rand in the paper).
    Random,
}

impl Probe {
    /// The GLSL constant.
    pub fn id(self) -> u32 {
        match self {
            Probe::Coherent => HASH_PROBE_COHERENT,
            Probe::Random => HASH_PROBE_RANDOM,
        }
    }

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Probe::Coherent => "coherent",
            Probe::Random => "random",
        }
    }
}

fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

fn coherent_offset(age: u32) -> u64 {
    if age <= 16 {
        COHERENT_OFFSETS[age as usize - 1] as u64
    } else {
        mix64(age as u64) >> 40
    }
}

/// ceil(2^64 / d): the multiplier of the division-free `x mod d` that the kernels use
/// (`fastmod32` in `glsl/include/hash/probe.glsl`; 0 for d = 1, where every remainder is 0).
pub fn fastmod_multiplier(d: u32) -> u64 {
    (u64::MAX / d.max(1) as u64).wrapping_add(1)
}

/// `key mod d` for any 64-bit key without a division, as the kernels compute it (`table_mod`
/// in `glsl/include/hash/probe.glsl`), given `m = fastmod_multiplier(d)`: the high half of
/// key · m is ⌊key / d⌋ or one more, and the remainder is corrected for the latter. The CPU
/// reference uses `%`; this mirror lets the tests check the kernels' arithmetic over every
/// edge case.
pub fn table_mod(key: u64, d: u32, m: u64) -> u32 {
    let q = ((key as u128 * m as u128) >> 64) as u64;
    let r = key.wrapping_sub(q.wrapping_mul(d as u64));
    let r = if r >= d as u64 {
        r.wrapping_add(d as u64)
    } else {
        r
    };
    if d == 1 {
        0
    } else {
        r as u32
    }
}

/// The slot that `key` probes at step `age` (1-based) in a table of `table_size` cells.
///
/// Coherent: (key + o_(age−1)) mod |H|, computed as ((key mod |H|) + (o mod |H|)) mod |H|.
/// Random: a 32-bit hash of (key, age) scaled to the table by a multiply and a shift.
pub fn probe_slot(probe: Probe, key: u64, age: u32, table_size: u32) -> u32 {
    let d = table_size as u64;
    match probe {
        Probe::Coherent => ((key % d + coherent_offset(age) % d) % d) as u32,
        Probe::Random => {
            (((mix64(key.wrapping_mul(16).wrapping_add(age as u64)) >> 32) * d) >> 32) as u32
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernels' division-free remainder, as GLSL computes it.
    fn fastmod32(x: u32, m: u64, d: u32) -> u32 {
        let low = m.wrapping_mul(x as u64);
        let t = (low as u32 as u64) * d as u64;
        let t2 = (low >> 32) * d as u64 + (t >> 32);
        (t2 >> 32) as u32
    }

    #[test]
    fn fastmod_is_exact() {
        let mut x = 0x9e3779b9u32;
        for d in [1u32, 3, 5, 7, 1_000_003, 7_624_331, 0x7fff_ffff, u32::MAX] {
            let m = fastmod_multiplier(d);
            for _ in 0..10_000 {
                x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                assert_eq!(fastmod32(x, m, d), x % d, "{x} mod {d}");
            }
            assert_eq!(fastmod32(u32::MAX, m, d), u32::MAX % d);
            assert_eq!(fastmod32(0, m, d), 0);
        }
    }

    /// The kernels' four-product high half of key · m, as GLSL computes it.
    fn mulhi_by_parts(key: u64, m: u64) -> u64 {
        let (k0, k1, m0, m1) = (key & 0xffff_ffff, key >> 32, m & 0xffff_ffff, m >> 32);
        let p01 = k0 * m1;
        let p10 = k1 * m0;
        let mid = ((k0 * m0) >> 32) + (p01 & 0xffff_ffff) + (p10 & 0xffff_ffff);
        k1 * m1 + (p01 >> 32) + (p10 >> 32) + (mid >> 32)
    }

    #[test]
    fn table_mod_is_exact_for_every_64_bit_key() {
        let mut x = 0x0123_4567_89ab_cdefu64;
        let mut divisors = vec![1u32, 2, 3, 5, 7, 64, 1 << 31, 1_000_003, 7_624_331];
        divisors.extend([0x7fff_ffff, 0x8000_0001, u32::MAX - 1, u32::MAX]);
        for _ in 0..200 {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            divisors.push((x >> 33) as u32 | 1);
            divisors.push((x >> 40) as u32 + 2);
        }
        for d in divisors {
            let m = fastmod_multiplier(d);
            let d64 = d as u64;
            let mut keys = vec![0u64, 1, u64::MAX, u64::MAX - 1, 1 << 32, (1 << 32) - 1];
            for k in [1u64, 2, 3, 1 << 20, (1 << 32) / d64.max(1), u64::MAX / d64] {
                let base = k.wrapping_mul(d64);
                keys.extend([base.wrapping_sub(1), base, base.wrapping_add(1)]);
            }
            for _ in 0..2_000 {
                x = x
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                keys.extend([x, x >> 31, x >> 40]);
            }
            for key in keys {
                assert_eq!(
                    mulhi_by_parts(key, m),
                    ((key as u128 * m as u128) >> 64) as u64
                );
                assert_eq!(table_mod(key, d, m) as u64, key % d64, "{key} mod {d}");
            }
        }
    }
}
