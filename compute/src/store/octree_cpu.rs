//! The plain-Rust octree texture: the same node pool, word for word, as the GPU build (nodes
//! allocated level by level in key order at the top of the pool), and the same lookups.

use super::octree::OctreeConfig;
use crate::hash::{morton_decode, morton_encode};
use std::collections::BTreeMap;

/// The CPU reference of [`OctreeStore`](super::OctreeStore).
pub struct OctreeCpu {
    /// N of each level.
    pub levels: Vec<u32>,
    /// Voxels per cell of each level.
    pub spans: Vec<u32>,
    /// The node pool (words up to the top).
    pub pool: Vec<u32>,
    /// First free address (units of 8 words).
    pub top: u32,
    nodes: Vec<BTreeMap<u64, u32>>,
}

fn div3(v: [u32; 3], d: u32) -> [u32; 3] {
    v.map(|c| c / d)
}

impl OctreeCpu {
    /// An empty tree (a root only).
    pub fn new(config: &OctreeConfig) -> OctreeCpu {
        let top = config.stride(0);
        OctreeCpu {
            levels: config.levels.clone(),
            spans: config.spans(),
            pool: vec![0; 8 * top as usize],
            top,
            nodes: vec![BTreeMap::new(); config.levels.len()],
        }
    }

    fn parent_address(&self, level: usize, key: u64) -> Option<u32> {
        if level == 0 {
            Some(0)
        } else {
            self.nodes[level].get(&key).copied()
        }
    }

    fn cell_word(&self, address: u32, level: usize, cell: [u32; 3]) -> usize {
        let n = self.levels[level];
        8 * address as usize + 1 + (cell[0] + n * (cell[1] + n * cell[2])) as usize
    }

    /// Adds voxels (`keys`, Morton) with their colours, then recomputes the averages.
    pub fn insert(&mut self, keys: &[u64], colours: &[u32]) {
        let depth = self.levels.len();
        for l in 1..depth {
            let span = self.spans[l - 1];
            let mut cand: Vec<u64> = keys
                .iter()
                .map(|&k| morton_encode(div3(morton_decode(k, 3), span), 3))
                .collect();
            cand.sort_unstable();
            cand.dedup();
            let stride = OctreeConfig::stride_of(self.levels[l]);
            for key in cand {
                if self.nodes[l].contains_key(&key) {
                    continue;
                }
                let address = self.top;
                self.top += stride;
                self.pool.resize(8 * self.top as usize, 0);
                self.nodes[l].insert(key, address);
                let c = morton_decode(key, 3);
                let n = self.levels[l - 1];
                let parent = self
                    .parent_address(l - 1, morton_encode(div3(c, n), 3))
                    .expect("parents are added first");
                let word = self.cell_word(parent, l - 1, c.map(|x| x % n));
                self.pool[word] = (1 << 24) | address;
            }
        }
        let last = depth - 1;
        let n = self.levels[last];
        for (&k, &colour) in keys.iter().zip(colours) {
            let v = morton_decode(k, 3);
            let parent = self
                .parent_address(last, morton_encode(div3(v, n), 3))
                .expect("built above");
            let word = self.cell_word(parent, last, v.map(|x| x % n));
            self.pool[word] = colour;
        }
        self.average();
    }

    /// Replaces the colours of stored voxels.
    pub fn update(&mut self, keys: &[u64], colours: &[u32]) {
        let last = self.levels.len() - 1;
        let n = self.levels[last];
        for (&k, &colour) in keys.iter().zip(colours) {
            let v = morton_decode(k, 3);
            let parent = self
                .parent_address(last, morton_encode(div3(v, n), 3))
                .expect("stored voxel");
            let word = self.cell_word(parent, last, v.map(|x| x % n));
            self.pool[word] = colour;
        }
        self.average();
    }

    fn average(&mut self) {
        for l in (0..self.levels.len()).rev() {
            let addresses: Vec<u32> = if l == 0 {
                vec![0]
            } else {
                self.nodes[l].values().copied().collect()
            };
            let cells = self.levels[l].pow(3) as usize;
            for a in addresses {
                let base = 8 * a as usize;
                let mut sum = [0u32; 4];
                let mut count = 0;
                for k in 0..cells {
                    let e = self.pool[base + 1 + k];
                    let c = match e >> 24 {
                        0 => continue,
                        1 => self.pool[8 * (e & 0xff_ffff) as usize],
                        _ => e,
                    };
                    for (ch, s) in sum.iter_mut().enumerate() {
                        *s += (c >> (8 * ch)) & 255;
                    }
                    count += 1;
                }
                self.pool[base] = if count == 0 {
                    0
                } else {
                    (0..4).fold(0, |acc, ch| {
                        acc | (((sum[ch] + count / 2) / count) << (8 * ch))
                    })
                };
            }
        }
    }

    /// The descent of `store_octree_texel`: the colour, or `None` where nothing is stored.
    pub fn texel(&self, voxel: [u32; 3]) -> Option<u32> {
        let mut address = 0;
        for l in 0..self.levels.len() {
            let c = div3(voxel, self.spans[l]).map(|x| x % self.levels[l]);
            let e = self.pool[self.cell_word(address, l, c)];
            match e >> 24 {
                0 => return None,
                1 => address = e & 0xff_ffff,
                _ => return Some(e),
            }
        }
        None
    }

    /// The descent of `store_octree_mip`: the average of the node at `depth` (RGBA8, 0 when
    /// the path is empty).
    pub fn mip(&self, voxel: [u32; 3], depth: usize) -> u32 {
        let mut address = 0;
        for l in 0..self.levels.len() {
            if l == depth {
                return self.pool[8 * address as usize];
            }
            let c = div3(voxel, self.spans[l]).map(|x| x % self.levels[l]);
            let e = self.pool[self.cell_word(address, l, c)];
            match e >> 24 {
                0 => return 0,
                1 => address = e & 0xff_ffff,
                _ => return e,
            }
        }
        0
    }
}
