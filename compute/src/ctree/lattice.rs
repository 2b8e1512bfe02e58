//! The primal lattice of a compressed tree: nodes sit at cell corners, and the nodes of a level
//! are a subset of the next finer level's, so an evaluation reads the 2^d corners of one cell
//! per level. The finest level has 2^n + 1 nodes per axis; level l ≥ 1 has 2^(l−1) + 1 with a
//! spacing of 2^(n−l+1) finest nodes; level 0 is the root, whose children are the 2^d corners
//! of the domain. A node p at level l has the children p + c·h_(l+1), c ∈ {0, 1}^d, that lie in
//! the domain (the slanted tree of the thesis, §4.1.3), so every node of level l + 1 has exactly
//! one parent: its position rounded down to level l's lattice.

/// Largest n of a 2D lattice (8,193² nodes).
pub const MAX_LEVELS_2D: u32 = 13;
/// Largest n of a 3D lattice (513³ nodes).
pub const MAX_LEVELS_3D: u32 = 9;

/// The geometry of a primal lattice of dimension 2 or 3 with 2^n + 1 nodes per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice {
    /// 2 or 3.
    pub dims: u32,
    /// log2 of the finest spacing count: the domain spans 2^n finest cells per axis.
    pub n: u32,
}

impl Lattice {
    /// The smallest lattice whose finest level holds `size` samples per axis.
    pub fn fitting(dims: u32, size: [u32; 3]) -> Lattice {
        let largest = size[..dims as usize]
            .iter()
            .copied()
            .max()
            .unwrap_or(1)
            .max(2);
        let mut n = 1;
        while (1u32 << n) + 1 < largest {
            n += 1;
        }
        Lattice { dims, n }
    }

    /// The finest level (levels run 0 = root ..= `finest()`).
    pub fn finest(&self) -> u32 {
        self.n + 1
    }

    /// Children per node in a full brood.
    pub fn brood(&self) -> u32 {
        1 << self.dims
    }

    /// Spacing of level `l` ≥ 1, in finest nodes.
    pub fn spacing(&self, l: u32) -> u32 {
        1 << (self.n + 1 - l)
    }

    /// Nodes per axis of level `l` ≥ 1.
    pub fn side(&self, l: u32) -> u32 {
        (1 << (l - 1)) + 1
    }

    /// Nodes of level `l` ≥ 1 (the full lattice).
    pub fn count(&self, l: u32) -> usize {
        (self.side(l) as usize).pow(self.dims)
    }

    /// Largest coordinate, in finest nodes.
    pub fn extent(&self) -> u32 {
        1 << self.n
    }

    /// Dense index of lattice coordinates `q` (in level-`l` units) within level `l`.
    pub fn index(&self, l: u32, q: [u32; 3]) -> usize {
        let m = self.side(l) as usize;
        let mut i = q[0] as usize + m * q[1] as usize;
        if self.dims == 3 {
            i += m * m * q[2] as usize;
        }
        i
    }

    /// Lattice coordinates (level-`l` units) of dense index `i`.
    pub fn coords(&self, l: u32, i: usize) -> [u32; 3] {
        let m = self.side(l) as usize;
        let z = if self.dims == 3 { i / (m * m) } else { 0 };
        let r = i - z * m * m;
        [(r % m) as u32, (r / m) as u32, z as u32]
    }

    /// Which child bits a node at level-`l` coordinates `q` may set: axis k can take the upper
    /// child unless the node lies on the domain's upper face. The root (`l` = 0) has all.
    pub fn open_axes(&self, l: u32, q: [u32; 3]) -> [bool; 3] {
        if l == 0 {
            return [true, true, self.dims == 3];
        }
        let last = self.side(l) - 1;
        [q[0] < last, q[1] < last, self.dims == 3 && q[2] < last]
    }

    /// The children a node has, given its open axes.
    pub fn child_count(&self, open: [bool; 3]) -> u32 {
        open[..self.dims as usize]
            .iter()
            .map(|&o| if o { 2 } else { 1 })
            .product()
    }

    /// The slot of child `c` (bit k = upper child along axis k) in its parent's record: its
    /// rank among the children the parent has, x fastest.
    pub fn slot(&self, open: [bool; 3], c: u32) -> u32 {
        let mut slot = 0;
        let mut stride = 1;
        for (k, &o) in open[..self.dims as usize].iter().enumerate() {
            if o {
                slot += stride * ((c >> k) & 1);
                stride *= 2;
            }
        }
        slot
    }

    /// Coordinates at level `l` + 1 of child `c` of the node at level-`l` coordinates `q`.
    pub fn child(&self, l: u32, q: [u32; 3], c: u32) -> [u32; 3] {
        let base = if l == 0 { [0; 3] } else { q.map(|v| 2 * v) };
        [
            base[0] + (c & 1),
            base[1] + ((c >> 1) & 1),
            base[2] + ((c >> 2) & 1),
        ]
    }

    /// The preorder rank key of a node at level `l` ≥ 1: its child indices from the root down,
    /// the root's first, as the digits of a Morton code (x the lowest bit of each digit).
    pub fn preorder_key(&self, l: u32, q: [u32; 3]) -> u64 {
        let mut key = 0u64;
        for bit in (0..l).rev() {
            for k in 0..self.dims {
                key = (key << 1) | ((q[(self.dims - 1 - k) as usize] >> bit) & 1) as u64;
            }
        }
        key
    }

    /// The nodes of level `l` ≥ 1 in preorder (dense indices).
    pub fn preorder(&self, l: u32) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.count(l)).collect();
        order.sort_by_key(|&i| self.preorder_key(l, self.coords(l, i)));
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_node_has_one_parent_and_slots_are_dense() {
        for dims in [2, 3] {
            let lat = Lattice { dims, n: 3 };
            for l in 0..lat.finest() {
                let parents = if l == 0 { 1 } else { lat.count(l) };
                let mut seen = vec![0u32; lat.count(l + 1)];
                for i in 0..parents {
                    let q = if l == 0 { [0; 3] } else { lat.coords(l, i) };
                    let open = lat.open_axes(l, q);
                    let mut slots = vec![];
                    for c in 0..lat.brood() {
                        let closed = (0..dims).any(|k| (c >> k) & 1 == 1 && !open[k as usize]);
                        if closed {
                            continue;
                        }
                        seen[lat.index(l + 1, lat.child(l, q, c))] += 1;
                        slots.push(lat.slot(open, c));
                    }
                    slots.sort();
                    let expect: Vec<u32> = (0..lat.child_count(open)).collect();
                    assert_eq!(slots, expect);
                }
                assert!(seen.iter().all(|&s| s == 1), "level {l}");
            }
        }
    }

    #[test]
    fn preorder_follows_the_child_indices() {
        let lat = Lattice { dims: 2, n: 2 };
        // Level 2 (3×3): the root's child 0 holds (0,0),(1,0),(0,1),(1,1) in that order.
        let order: Vec<[u32; 3]> = lat.preorder(2).iter().map(|&i| lat.coords(2, i)).collect();
        assert_eq!(&order[..4], &[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]);
        assert_eq!(Lattice::fitting(2, [256, 256, 1]).n, 8);
        assert_eq!(Lattice::fitting(2, [257, 100, 1]).n, 8);
        assert_eq!(Lattice::fitting(2, [258, 100, 1]).n, 9);
    }
}
