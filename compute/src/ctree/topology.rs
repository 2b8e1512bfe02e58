//! What the same pruned tree's topology costs in the encodings the thesis compares (§4.1.3),
//! in bytes per node, beside the compact one measured in [`CtreeStats`]:
//! - pointer tree: every node holds 2^d 32-bit child pointers, 4·2^d bytes;
//! - sibling tree: broods are contiguous, one 32-bit pointer per node, 4 bytes;
//! - autumnal tree: leaves lifted into their parent, a pointer per internal node and one bit
//!   per node saying whether a child is a leaf, (4·internal + nodes/8) / nodes (the thesis prints
//!   4·2^(d−1) + 1/8, but its quadtree figure of 1.125 is 4·2^(−d) + 1/8 of a complete tree).

use super::tree::CtreeStats;

/// Topology bytes per node of each encoding, for one tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TopologyCosts {
    /// Pointer tree.
    pub pointer: f64,
    /// Sibling tree.
    pub sibling: f64,
    /// Autumnal tree.
    pub autumnal: f64,
    /// The compact encoding with the forest, as packed.
    pub compact: f64,
    /// The compact encoding packed from the root (no forest): pointers and padding.
    pub compact_rooted: f64,
}

impl TopologyCosts {
    /// The costs of the tree `stats` describes, of dimension `dims`.
    pub fn of(stats: &CtreeStats, dims: u32) -> TopologyCosts {
        let nodes = stats.nodes as f64;
        let internal = stats.internal_nodes as f64;
        let rooted: u64 = stats
            .rows
            .iter()
            .map(|r| r.padding + if r.level > 0 { r.internal } else { 0 })
            .sum();
        TopologyCosts {
            pointer: 4.0 * (1u32 << dims) as f64,
            sibling: 4.0,
            autumnal: (4.0 * internal + nodes / 8.0) / nodes,
            compact: stats.topology_bytes as f64 / nodes,
            compact_rooted: rooted as f64 / nodes,
        }
    }
}
