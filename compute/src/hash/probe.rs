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

/// The slot that `key` probes at step `age` (1-based) in a table of `table_size` cells.
pub fn probe_slot(probe: Probe, key: u64, age: u32, table_size: u32) -> u32 {
    match probe {
        Probe::Coherent => (key.wrapping_add(coherent_offset(age)) % table_size as u64) as u32,
        Probe::Random => {
            (mix64(key.wrapping_mul(16).wrapping_add(age as u64)) % table_size as u64) as u32
        }
    }
}
