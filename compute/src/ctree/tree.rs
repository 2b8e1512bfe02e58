//! A compressed random-access tree: the forested mipmap (the dense levels 1..=F of the
//! reconstructed values, as i16, and at level F an indirection table of u32 addresses of the
//! clipped subtrees' records) and the packed records of the levels below F. F is chosen for the
//! fewest bytes in all; the packing below F does not depend on it.

use super::error::CtreeError;
use super::field::{ScalarField, VALUE_FRAC_BITS};
use super::lattice::Lattice;
use super::pack::{place, LevelPacking, Packing};
use super::residuals::{child_exists, Residuals};

pub use crate::shader_constants::CTREE_NO_SUBTREE as NO_SUBTREE;

/// How a tree is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CtreeOptions {
    /// The quantization step of the finest level, in grey levels (> 0). Every reconstructed
    /// node lies within half its level's step of the field; coarser steps prune more.
    pub step: f32,
    /// The forest's level F (1 ..= finest), or `None` for the F with the fewest bytes.
    pub forest: Option<u32>,
    /// Which nodes past the field's samples code a residual.
    pub border: Border,
}

/// What the lattice's nodes past the field's samples (it is 2^n + 1 a side) code. Lookups
/// clamp to the samples, so these nodes are only ever predictions for their neighbours inside;
/// which choice costs fewer bytes depends on the content (`bench ctree` measures both).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Border {
    /// At each level, the first node past each border codes the border's value (an anchor for
    /// the cells that hold samples); the nodes further out code nothing.
    #[default]
    Anchored,
    /// No node past the samples codes anything: they keep their predictions.
    Free,
}

impl CtreeOptions {
    /// Checks the options for `field`; returns the step in fixed point.
    pub fn validate(&self, field: &ScalarField) -> Result<i32, CtreeError> {
        let lat = field.lattice();
        if !(self.step.is_finite() && self.step > 0.0 && self.step <= 256.0) {
            return Err(CtreeError::Param {
                field: "step",
                value: self.step.to_string(),
                why: "must be a number of grey levels in (0, 256]".into(),
            });
        }
        if let Some(f) = self.forest {
            if f < 1 || f > lat.finest() {
                return Err(CtreeError::Param {
                    field: "forest",
                    value: f.to_string(),
                    why: format!("must be a level in 1..={} for this field", lat.finest()),
                });
            }
        }
        Ok(((self.step * (1 << VALUE_FRAC_BITS) as f32).round() as i32).max(1))
    }
}

impl Default for CtreeOptions {
    fn default() -> Self {
        CtreeOptions {
            step: 1.0,
            forest: None,
            border: Border::Anchored,
        }
    }
}

/// One row of the thesis' Table 4.2 for a tree packed from the root (no forest).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelRow {
    /// The level (0 = root).
    pub level: u32,
    /// Nodes kept at this level (children of internal nodes).
    pub nodes: u64,
    /// Of which internal (records).
    pub internal: u64,
    /// The offset scale s_l of this level's records (1 at the finest level).
    pub scale: u32,
    /// Padding bytes before this level's children's blocks.
    pub padding: u64,
}

/// Where the bytes of a tree go.
#[derive(Clone, Debug, PartialEq)]
pub struct CtreeStats {
    /// Table 4.2's rows, packed from the root.
    pub rows: Vec<LevelRow>,
    /// The forest level F.
    pub forest: u32,
    /// Bytes of the tree packed from the root (header, root record and all blocks).
    pub rooted_bytes: u64,
    /// Nodes of the tree (every level, pruned), the count the bytes per node divide by.
    pub nodes: u64,
    /// Topology bytes: pointer bytes and padding below F, and the indirection table.
    pub topology_bytes: u64,
    /// Internal nodes of the tree (every level).
    pub internal_nodes: u64,
}

/// A field compressed into a tree.
#[derive(Clone, Debug)]
pub struct CompressedTree {
    /// The lattice.
    pub lattice: Lattice,
    /// The field's own size (samples per axis).
    pub size: [u32; 3],
    /// Steps of levels 0..=L (fixed point).
    pub steps: Vec<i32>,
    /// Offset scales of levels 0..L.
    pub scales: Vec<u32>,
    /// The forest level F.
    pub forest: u32,
    /// Dense reconstructed values of levels 1..=F, one after another.
    pub mipmap: Vec<i16>,
    /// Start of each level 1..=F in `mipmap` (index l − 1).
    pub mip_starts: Vec<u32>,
    /// Byte address in `bytes` of each level-F node's record, or [`NO_SUBTREE`].
    pub indirection: Vec<u32>,
    /// The packed records.
    pub bytes: Vec<u8>,
    /// Where the bytes go.
    pub stats: CtreeStats,
}

/// Bytes of the header: dims, n, L, F, then per level its step and scale.
pub fn header_bytes(lat: &Lattice) -> u64 {
    4 * (4 + 2 * (lat.finest() as u64 + 1))
}

/// Bytes of the forest at level `f`: the pyramid's i16 values and the u32 indirection table.
pub fn forest_bytes(lat: &Lattice, f: u32) -> u64 {
    let pyramid: u64 = (1..=f).map(|l| lat.count(l) as u64).sum();
    2 * pyramid + 4 * lat.count(f) as u64
}

impl CompressedTree {
    /// Quantizes, prunes and packs `field`.
    pub fn build(field: &ScalarField, params: &CtreeOptions) -> Result<CompressedTree, CtreeError> {
        let step = params.validate(field)?;
        let res = Residuals::build(field, step, params.border);
        let packing = Packing::build(&res);
        Ok(Self::assemble(field.size, &res, &packing, params.forest))
    }

    /// Lays out the forest and the blocks below it.
    pub fn assemble(
        size: [u32; 3],
        res: &Residuals,
        packing: &Packing,
        forest: Option<u32>,
    ) -> CompressedTree {
        let lat = res.lattice;
        let finest = lat.finest();
        let subtree_bytes = |f: u32| packing.blocks[f as usize].iter().sum::<u64>();
        let total = |f: u32| header_bytes(&lat) + forest_bytes(&lat, f) + subtree_bytes(f);
        let f = forest.unwrap_or_else(|| {
            (1..=finest)
                .min_by_key(|&f| (total(f), f))
                .expect("a lattice has a level")
        });
        let mut mipmap = Vec::new();
        let mut mip_starts = Vec::new();
        for l in 1..=f {
            mip_starts.push(mipmap.len() as u32);
            mipmap.extend(res.values[l as usize].iter().map(|&v| v as i16));
        }
        // Addresses: level F's blocks one after another in preorder, then down the levels.
        let mut address: Vec<u64> = vec![NO_SUBTREE as u64; lat.count(f)];
        let mut top = 0u64;
        for i in lat.preorder(f) {
            if res.internal[f as usize][i] {
                address[i] = top;
                top += packing.blocks[f as usize][i];
            }
        }
        let mut bytes = vec![0u8; top as usize];
        let indirection = address.iter().map(|&a| a as u32).collect();
        for l in f..finest {
            let scale = packing.levels[l as usize].scale as u64;
            let mut below = vec![NO_SUBTREE as u64; lat.count(l + 1)];
            for (i, &a) in address.iter().enumerate() {
                if a == NO_SUBTREE as u64 {
                    continue;
                }
                let q = lat.coords(l, i);
                let open = lat.open_axes(l, q);
                let size = 1 + lat.child_count(open) as u64;
                bytes[a as usize] = code_byte(res.codes[l as usize][i]);
                let kids: Vec<(u32, usize)> = (0..lat.brood())
                    .filter(|&c| child_exists(&lat, open, c))
                    .map(|c| (c, lat.index(l + 1, lat.child(l, q, c))))
                    .collect();
                let blocks: Vec<u64> = kids
                    .iter()
                    .map(|&(_, j)| packing.blocks[l as usize + 1][j])
                    .filter(|&b| b > 0)
                    .collect();
                let (offsets, _) = place(&blocks, scale).expect("packed scale fits");
                let mut next = offsets.iter();
                for &(c, j) in &kids {
                    let slot = a + 1 + lat.slot(open, c) as u64;
                    if packing.blocks[l as usize + 1][j] > 0 {
                        let y = *next.next().expect("an offset per internal child");
                        bytes[slot as usize] = 0x80 | (y / scale) as u8;
                        below[j] = a + size + y;
                    } else {
                        bytes[slot as usize] = code_byte(res.codes[l as usize + 1][j]);
                    }
                }
            }
            address = below;
        }
        let stats = Self::stats(res, packing, f, &lat);
        CompressedTree {
            lattice: lat,
            size,
            steps: res.steps.clone(),
            scales: packing.levels.iter().map(|p| p.scale).collect(),
            forest: f,
            mipmap,
            mip_starts,
            indirection,
            bytes,
            stats,
        }
    }

    fn stats(res: &Residuals, packing: &Packing, f: u32, lat: &Lattice) -> CtreeStats {
        let finest = lat.finest();
        let rows: Vec<LevelRow> = (0..=finest)
            .map(|l| {
                let p = packing
                    .levels
                    .get(l as usize)
                    .cloned()
                    .unwrap_or(LevelPacking {
                        scale: 1,
                        ..Default::default()
                    });
                LevelRow {
                    level: l,
                    nodes: res.kept(l) as u64,
                    internal: res.internal[l as usize].iter().filter(|&&b| b).count() as u64,
                    scale: p.scale,
                    padding: p.padding,
                }
            })
            .collect();
        let rooted_bytes = header_bytes(lat) + packing.blocks[0][0].max(1 + lat.brood() as u64);
        let nodes = rows.iter().map(|r| r.nodes).sum();
        // Pointer bytes: one per internal node below F; padding of levels F.. below.
        let pointers: u64 = rows[f as usize + 1..].iter().map(|r| r.internal).sum();
        let padding: u64 = rows[f as usize..].iter().map(|r| r.padding).sum();
        let topology_bytes = pointers + padding + 4 * lat.count(f) as u64;
        CtreeStats {
            rows: rows.clone(),
            forest: f,
            rooted_bytes,
            nodes,
            topology_bytes,
            internal_nodes: rows.iter().map(|r| r.internal).sum(),
        }
    }

    /// Bytes of the whole structure: header, forest and records.
    pub fn size_bytes(&self) -> u64 {
        header_bytes(&self.lattice)
            + forest_bytes(&self.lattice, self.forest)
            + self.bytes.len() as u64
    }

    /// Bits per sample of the field (its own size, not the lattice's).
    pub fn bits_per_sample(&self) -> f64 {
        let samples: u64 = self.size.iter().map(|&s| s as u64).product();
        8.0 * self.size_bytes() as f64 / samples as f64
    }

    /// Topology bytes per node of the tree.
    pub fn topology_per_node(&self) -> f64 {
        self.stats.topology_bytes as f64 / self.stats.nodes as f64
    }
}

/// A 7-bit code in a byte, high bit clear.
pub fn code_byte(code: i8) -> u8 {
    (code as u8) & 0x7F
}

/// The code of a byte's low 7 bits, sign-extended.
pub fn byte_code(b: u8) -> i32 {
    (((b & 0x7F) << 1) as i8 >> 1) as i32
}
