//! The blocked variant for trilinear filtering: keys are blocks of b×b×b interpolation cells,
//! and each slot holds the (b+1)³ texels those cells read, borders duplicated between
//! neighbouring blocks, so a trilinear lookup reads one offset and then one block.
//!
//! Layout (also in `glsl/include/hash/perfect_blocked.glsl`): interpolation cell j (j in
//! 0..=R per axis) spans the voxel centres j−1 and j; block B = j / b covers the cells
//! B·b .. B·b + b − 1, so it needs the voxels B·b − 1 .. B·b + b − 1 (clamped onto the grid):
//! texel t ∈ [0, b]³ of the block is voxel clamp(B·b − 1 + t), stored at word
//! t.x + (b+1)·(t.y + (b+1)·t.z) of the slot's (b+1)³ words (RGBA8 each). Larger b means fewer
//! keys (less Φ, fewer empty slots) but more duplicated border texels; b is chosen to
//! minimize the total bytes.

use super::super::error::HashError;
use super::super::keys::{morton_decode, morton_encode, KeyLayout, Universe};
use super::cpu::build_perfect_cpu;
use super::gpu::{PerfectHashGpu, PerfectParams};
use super::kernels::PerfectKernels;
use super::sizes::PerfectSizes;
use super::table::{table_bytes, PerfectAccess, PerfectConfig, PerfectHash};
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult};
use glam::{UVec3, Vec3, Vec4};
use std::sync::Arc;

/// Block sizes considered.
pub const BLOCK_SIZES: std::ops::RangeInclusive<u32> = 1..=4;

/// The block geometry of a blocked table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockedLayout {
    /// b: cells per block edge.
    pub block: u32,
    /// R: voxels per axis of the texture.
    pub resolution: u32,
}

impl BlockedLayout {
    /// Texels per block edge: b + 1.
    pub fn side(&self) -> u32 {
        self.block + 1
    }

    /// Words per slot: (b+1)³.
    pub fn block_words(&self) -> u32 {
        self.side().pow(3)
    }

    /// The universe of block keys (Morton): ceil((R+1)/b) blocks per axis.
    pub fn universe(&self) -> Result<Universe, HashError> {
        let e = (self.resolution + 1).div_ceil(self.block);
        Universe::new_3d([e; 3], KeyLayout::Morton)
    }

    /// The voxel of texel `t` of block `b`.
    pub fn texel_voxel(&self, b: [u32; 3], t: [u32; 3]) -> [u32; 3] {
        std::array::from_fn(|a| {
            (b[a] as i64 * self.block as i64 - 1 + t[a] as i64).clamp(0, self.resolution as i64 - 1)
                as u32
        })
    }
}

/// The memory of one block size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockChoice {
    /// b.
    pub block: u32,
    /// Distinct blocks (keys of the hash).
    pub blocks: usize,
    /// Sizes the construction settled on.
    pub sizes: PerfectSizes,
    /// Total bytes: Φ plus |H|³ blocks of (b+1)³ words.
    pub bytes: u64,
}

/// The block keys (Morton) of interpolation cells given as Morton keys of the shifted grid.
pub fn block_keys(cells: &[u64], block: u32) -> Vec<u64> {
    let mut keys: Vec<u64> = cells
        .iter()
        .map(|&c| morton_encode(morton_decode(c, 3).map(|x| x / block), 3))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// Builds the hash for every b in [`BLOCK_SIZES`] on the CPU and reports its bytes.
///
/// # Errors
/// As [`build_perfect_cpu`].
pub fn blocked_sizes(cells: &[u64], resolution: u32) -> Result<Vec<BlockChoice>, HashError> {
    BLOCK_SIZES
        .map(|block| {
            let layout = BlockedLayout { block, resolution };
            let keys = block_keys(cells, block);
            let t = build_perfect_cpu(
                layout.universe()?,
                &keys,
                &vec![0; keys.len()],
                PerfectConfig::default(),
            )?;
            Ok(BlockChoice {
                block,
                blocks: keys.len(),
                sizes: t.sizes,
                bytes: table_bytes(&t.sizes, PerfectAccess::Constrained, layout.block_words()),
            })
        })
        .collect()
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct BlockedQueryPush<'a> {
        table: PerfectParams<'a>,
        positions: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        block: u32,
        resolution: u32,
    }
}

/// A blocked perfect hash on the host (constrained access: only positions whose footprint
/// cell was given may be looked up).
#[derive(Clone, Debug)]
pub struct BlockedPerfectHash {
    /// Block geometry.
    pub layout: BlockedLayout,
    /// The hash of block keys; `data` holds (b+1)³ texels per slot.
    pub table: PerfectHash,
    /// Bytes for every block size tried (empty when b was given).
    pub choices: Vec<BlockChoice>,
}

impl BlockedPerfectHash {
    /// Builds a blocked table on the CPU for the interpolation cells `cells` (Morton keys of
    /// the shifted grid of resolution `resolution`, as `Voxelizer::cells` returns them) with
    /// texel colours `texel(voxel)`. `block: None` tries b = 1..=4 and keeps the smallest.
    ///
    /// # Errors
    /// A block size outside 1..=4, bad resolutions, and the construction's errors.
    pub fn build(
        cells: &[u64],
        resolution: u32,
        texel: impl Fn([u32; 3]) -> u32,
        block: Option<u32>,
    ) -> Result<Self, HashError> {
        let (block, choices) = match block {
            Some(b) if BLOCK_SIZES.contains(&b) => (b, Vec::new()),
            Some(b) => {
                return Err(HashError::InvalidArgument(format!(
                    "block size {b} is outside {BLOCK_SIZES:?}"
                )))
            }
            None => {
                let choices = blocked_sizes(cells, resolution)?;
                let best = choices
                    .iter()
                    .min_by_key(|c| c.bytes)
                    .map_or(1, |c| c.block);
                (best, choices)
            }
        };
        let layout = BlockedLayout { block, resolution };
        let keys = block_keys(cells, block);
        let universe = layout.universe()?;
        let mut table = build_perfect_cpu(
            universe,
            &keys,
            &vec![0; keys.len()],
            PerfectConfig::default(),
        )?;
        let bw = layout.block_words() as usize;
        let side = layout.side();
        let mut data = vec![0u32; table.sizes.slots() as usize * bw];
        for &k in &keys {
            let b = universe.point(k);
            let s = table.slot(b) as usize;
            for tz in 0..side {
                for ty in 0..side {
                    for tx in 0..side {
                        let w = (tx + side * (ty + side * tz)) as usize;
                        data[s * bw + w] = texel(layout.texel_voxel(b, [tx, ty, tz]));
                    }
                }
            }
        }
        table.data = data;
        Ok(BlockedPerfectHash {
            layout,
            table,
            choices,
        })
    }

    /// CPU reference of `perfect_blocked_trilinear`: the filtered colour at `pos`.
    pub fn trilinear(&self, pos: Vec3) -> Vec4 {
        let r = self.layout.resolution;
        let q = pos * r as f32 - 0.5;
        let fl = q.floor();
        let f = q - fl;
        let j = (fl.as_ivec3() + 1).clamp(glam::IVec3::ZERO, glam::IVec3::splat(r as i32));
        let j = j.as_uvec3();
        let b = j / self.layout.block;
        let local = j - b * self.layout.block;
        let s = self.table.slot(b.to_array()) as usize;
        let bw = self.layout.block_words() as usize;
        let side = self.layout.side();
        (0..8u32)
            .map(|o| {
                let d = UVec3::new(o & 1, (o >> 1) & 1, o >> 2);
                let t = local + d;
                let w = (0..3)
                    .map(|a| if d[a] == 1 { f[a] } else { 1.0 - f[a] })
                    .product::<f32>();
                let word = self.table.data[s * bw + (t.x + side * (t.y + side * t.z)) as usize];
                crate::texel::unpack_rgba8(word) * w
            })
            .sum()
    }

    /// Total bytes (Φ and the blocks).
    pub fn bytes(&self) -> u64 {
        table_bytes(
            &self.table.sizes,
            PerfectAccess::Constrained,
            self.layout.block_words(),
        )
    }

    /// Uploads the table for GPU lookups.
    pub fn upload(&self, kernels: &Arc<PerfectKernels>) -> Result<PerfectHashGpu, HashError> {
        PerfectHashGpu::upload_words(kernels, &self.table, self.layout.block_words())
    }

    /// Trilinear lookups on the GPU through `glsl/include/hash/perfect_blocked.glsl`.
    pub fn query_gpu(&self, table: &PerfectHashGpu, positions: &[Vec3]) -> GpuResult<Vec<Vec4>> {
        let kernels = table.kernels();
        let gpu = &kernels.gpu;
        let flat: Vec<f32> = positions.iter().flat_map(|p| p.to_array()).collect();
        let n = positions.len();
        let pos = GpuBuffer::from_slice(gpu, "blocked query positions", &pad(flat))?;
        let out = GpuBuffer::<f32>::new(gpu, "blocked query results", 4 * n.max(1))?;
        gpu.submit(|rec| {
            if n == 0 {
                return Ok(());
            }
            let push = BlockedQueryPush {
                table: table.params(),
                positions: pos.address(),
                results: out.address(),
                n: n as u32,
                block: self.layout.block,
                resolution: self.layout.resolution,
            };
            let k = gpu.kernel(&crate::kernels::hash::PERFECT_BLOCKED_QUERY)?;
            rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
        })?;
        let v = out.read()?;
        Ok((0..n)
            .map(|i| Vec4::from_slice(&v[4 * i..4 * i + 4]))
            .collect())
    }
}

fn pad(v: Vec<f32>) -> Vec<f32> {
    if v.is_empty() {
        vec![0.0; 3]
    } else {
        v
    }
}
