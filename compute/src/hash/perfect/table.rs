//! A finished perfect spatial hash held on the host: the packed offset table Φ, the data table
//! H of `u32` payloads and, for unconstrained access, a tag per slot; with the CPU lookup that
//! is the reference of the GLSL include.

use super::super::keys::Universe;
use super::function::{bucket, slot};
use super::sizes::PerfectSizes;

/// Which queries the table answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PerfectAccess {
    /// Only defined keys are ever queried (the texturing case): no keys are stored, and an
    /// absent key reads some other key's payload.
    Constrained,
    /// Any point may be queried: each slot also stores 1 + h1(p) of its key (0 when empty).
    /// Since (h0, h1) is injective on the universe and h0(p) = slot − Φ[h1(p)], equal tags
    /// prove that the stored key is the queried one.
    Unconstrained,
}

/// How a perfect hash is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PerfectConfig {
    /// Constrained or unconstrained access.
    pub access: PerfectAccess,
    /// |Φ| per axis of the first attempt; `None` starts at σ = 1/(2d) (4 bits per key with
    /// 8-bit components). Either way |Φ| is then made coprime with |H| and large enough.
    pub initial_phi: Option<u32>,
    /// Attempts before giving up (each failure grows |Φ|^d by 10 %).
    pub max_attempts: u32,
}

impl Default for PerfectConfig {
    fn default() -> Self {
        PerfectConfig {
            access: PerfectAccess::Constrained,
            initial_phi: None,
            max_attempts: 40,
        }
    }
}

/// One construction attempt at fixed sizes.
#[derive(Clone, Debug, PartialEq)]
pub struct PerfectAttempt {
    /// The sizes tried.
    pub sizes: PerfectSizes,
    /// Offset-table bits per key at these sizes.
    pub bits_per_key: f64,
    /// Why it failed; `None` for the attempt that succeeded.
    pub failure: Option<String>,
}

/// What a construction did: every attempt, the failed ones with their reason.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PerfectReport {
    /// Keys hashed.
    pub keys: usize,
    /// Attempts in order; the last one succeeded.
    pub attempts: Vec<PerfectAttempt>,
}

impl PerfectReport {
    /// Number of times |Φ| was grown.
    pub fn growths(&self) -> usize {
        self.attempts.len().saturating_sub(1)
    }
}

/// A perfect spatial hash on the host.
#[derive(Clone, Debug, PartialEq)]
pub struct PerfectHash {
    /// The key universe.
    pub universe: Universe,
    /// |H|, |Φ| and the offset width.
    pub sizes: PerfectSizes,
    /// Constrained or unconstrained.
    pub access: PerfectAccess,
    /// Φ packed as described in [`super::function::pack_offsets`].
    pub offsets: Vec<u32>,
    /// |H|^d payloads (unused slots hold 0).
    pub data: Vec<u32>,
    /// Unconstrained access: |H|^d tags, 1 + h1(p) of the slot's key, 0 when empty.
    pub tags: Option<Vec<u32>>,
    /// How the sizes were found.
    pub report: PerfectReport,
}

impl PerfectHash {
    /// The slot of point `p` (any point of the universe).
    pub fn slot(&self, p: [u32; 3]) -> u32 {
        slot(&self.sizes, &self.offsets, p)
    }

    /// The payload of point `p`: with constrained access whatever its slot holds (defined
    /// points only), with unconstrained access `None` for points that are not keys or lie
    /// outside the universe.
    pub fn lookup(&self, p: [u32; 3]) -> Option<u32> {
        let s = self.slot(p) as usize;
        match &self.tags {
            None => Some(self.data[s]),
            Some(tags) => (self.universe.contains(p) && tags[s] == bucket(&self.sizes, p) + 1)
                .then(|| self.data[s]),
        }
    }

    /// [`PerfectHash::lookup`] by universe key; keys outside the universe are `None`.
    pub fn lookup_key(&self, key: u64) -> Option<u32> {
        if key >= self.universe.key_count() {
            return None;
        }
        let p = self.universe.point(key);
        if !self.universe.contains(p) {
            return None;
        }
        self.lookup(p)
    }

    /// Bytes of Φ, H and the tags, as stored on the GPU.
    pub fn bytes(&self) -> u64 {
        table_bytes(&self.sizes, self.access, 1)
    }

    /// Offset-table bits per key (padding excluded).
    pub fn bits_per_key(&self) -> f64 {
        self.sizes.bits_per_key(self.report.keys)
    }
}

/// Bytes of a table: packed Φ, `words_per_slot` payload words per slot, and a tag per slot
/// for unconstrained access.
pub fn table_bytes(sizes: &PerfectSizes, access: PerfectAccess, words_per_slot: u32) -> u64 {
    let slots = sizes.slots() as u64;
    let tags = if access == PerfectAccess::Unconstrained {
        slots * 4
    } else {
        0
    };
    sizes.offset_words() as u64 * 4 + slots * words_per_slot as u64 * 4 + tags
}
