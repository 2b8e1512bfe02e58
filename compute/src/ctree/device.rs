//! A compressed tree on the device: its four buffers and the record (`CtreeParams`) through
//! which any kernel reads it with `glsl/include/ctree/lookup.glsl`.

use super::lattice::Lattice;
use super::tree::CompressedTree;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Kernel, PushBlock};
use crate::kernels::ctree as kernels;
use glam::{UVec3, UVec4, Vec4};

crate::push_block! {
    /// What `ctree/lookup.glsl` receives: the `CtreeParams` struct, field for field.
    #[derive(Clone, Copy, Debug, Default)]
    pub struct CtreeParams<'a> {
        /// The packed records, four bytes per word.
        pub bytes: DeviceAddress<'a>,
        /// The forest's i16 values, two per word.
        pub mipmap: DeviceAddress<'a>,
        /// The level-F record addresses.
        pub indirection: DeviceAddress<'a>,
        /// Steps, scales and pyramid starts.
        pub levels: DeviceAddress<'a>,
        /// 2 or 3.
        pub dims: u32,
        /// The lattice's n.
        pub n: u32,
        /// The forest level F.
        pub forest: u32,
        /// The field's samples per axis.
        pub size: UVec3,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LookupPush<'a> {
        tree: CtreeParams<'a>,
        points: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        mode: u32,
    }
}

/// A device tree read back.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DownloadedTree {
    /// The forest level F.
    pub forest: u32,
    /// The packed records.
    pub bytes: Vec<u8>,
    /// The pyramid's values.
    pub mipmap: Vec<i16>,
    /// The indirection table.
    pub indirection: Vec<u32>,
    /// Steps, scales and pyramid starts.
    pub levels: Vec<u32>,
}

impl DownloadedTree {
    /// The same parts of a host build.
    pub fn of(tree: &CompressedTree) -> DownloadedTree {
        DownloadedTree {
            forest: tree.forest,
            bytes: tree.bytes.clone(),
            mipmap: tree.mipmap.clone(),
            indirection: tree.indirection.clone(),
            levels: level_words(tree),
        }
    }
}

/// A tree's buffers on one device.
pub struct DeviceTree {
    gpu: Gpu,
    /// The packed records as words (at least one word).
    pub bytes: GpuBuffer<u32>,
    /// The forest's values as words.
    pub mipmap: GpuBuffer<u32>,
    /// The indirection table.
    pub indirection: GpuBuffer<u32>,
    /// Steps (i32 bits), scales and pyramid starts.
    pub levels: GpuBuffer<u32>,
    byte_len: usize,
    pyramid_len: usize,
    dims: u32,
    n: u32,
    forest: u32,
    size: [u32; 3],
}

/// Bytes to little-endian words, zero-padded (at least one word).
pub fn words_of_bytes(bytes: &[u8]) -> Vec<u32> {
    let mut words = vec![0u32; bytes.len().div_ceil(4).max(1)];
    for (i, &b) in bytes.iter().enumerate() {
        words[i / 4] |= (b as u32) << (8 * (i % 4));
    }
    words
}

/// i16 values to words, two per word (at least one word).
pub fn words_of_i16(values: &[i16]) -> Vec<u32> {
    let mut words = vec![0u32; values.len().div_ceil(2).max(1)];
    for (i, &v) in values.iter().enumerate() {
        words[i / 2] |= (v as u16 as u32) << (16 * (i % 2));
    }
    words
}

/// The level table of `ctree/lookup.glsl`: steps of levels 0..=L, scales of 0..L, pyramid
/// starts of 1..=F.
pub fn level_words(tree: &CompressedTree) -> Vec<u32> {
    let mut words: Vec<u32> = tree.steps.iter().map(|&s| s as u32).collect();
    words.extend(&tree.scales);
    words.extend(&tree.mip_starts);
    words
}

impl DeviceTree {
    /// Uploads a tree built on the host.
    pub fn upload(gpu: &Gpu, tree: &CompressedTree) -> GpuResult<DeviceTree> {
        Ok(DeviceTree {
            gpu: gpu.clone(),
            bytes: GpuBuffer::from_slice(gpu, "ctree records", &words_of_bytes(&tree.bytes))?,
            mipmap: GpuBuffer::from_slice(gpu, "ctree pyramid", &words_of_i16(&tree.mipmap))?,
            indirection: GpuBuffer::from_slice(gpu, "ctree indirection", &tree.indirection)?,
            levels: GpuBuffer::from_slice(gpu, "ctree levels", &level_words(tree))?,
            byte_len: tree.bytes.len(),
            pyramid_len: tree.mipmap.len(),
            dims: tree.lattice.dims,
            n: tree.lattice.n,
            forest: tree.forest,
            size: tree.size,
        })
    }

    /// A tree from buffers a device build filled.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn from_parts(
        gpu: &Gpu,
        bytes: GpuBuffer<u32>,
        byte_len: usize,
        mipmap: GpuBuffer<u32>,
        pyramid_len: usize,
        indirection: GpuBuffer<u32>,
        levels: GpuBuffer<u32>,
        (lattice, forest, size): (Lattice, u32, [u32; 3]),
    ) -> DeviceTree {
        DeviceTree {
            gpu: gpu.clone(),
            bytes,
            mipmap,
            indirection,
            levels,
            byte_len,
            pyramid_len,
            dims: lattice.dims,
            n: lattice.n,
            forest,
            size,
        }
    }

    /// Reads the tree back: its packed bytes, pyramid values, indirection table and level
    /// table (as [`level_words`] lays it out), to compare with a host build.
    pub fn download(&self) -> GpuResult<DownloadedTree> {
        let words = self.bytes.read()?;
        let bytes = (0..self.byte_len)
            .map(|i| (words[i / 4] >> (8 * (i % 4))) as u8)
            .collect();
        let pyramid = self.mipmap.read()?;
        let mipmap = (0..self.pyramid_len)
            .map(|i| (pyramid[i / 2] >> (16 * (i % 2))) as u16 as i16)
            .collect();
        Ok(DownloadedTree {
            forest: self.forest,
            bytes,
            mipmap,
            indirection: self.indirection.read()?,
            levels: self.levels.read()?,
        })
    }

    /// The forest level F.
    pub fn forest(&self) -> u32 {
        self.forest
    }

    /// Bytes of the structure (as [`CompressedTree::size_bytes`] counts them).
    pub fn size_bytes(&self) -> u64 {
        let lattice = Lattice {
            dims: self.dims,
            n: self.n,
        };
        super::tree::header_bytes(&lattice)
            + super::tree::forest_bytes(&lattice, self.forest)
            + self.byte_len as u64
    }

    /// The record kernels read the tree through.
    pub fn params(&self) -> CtreeParams<'_> {
        CtreeParams {
            bytes: self.bytes.address(),
            mipmap: self.mipmap.address(),
            indirection: self.indirection.address(),
            levels: self.levels.address(),
            dims: self.dims,
            n: self.n,
            forest: self.forest,
            size: UVec3::from_array(self.size),
        }
    }

    fn run_lookup(&self, points: GpuBuffer<u32>, n: usize, mode: u32) -> GpuResult<Vec<u32>> {
        let results = GpuBuffer::<u32>::zeroed(&self.gpu, "ctree lookup results", n.max(1))?;
        let kernel = self.gpu.kernel(&kernels::CTREE_LOOKUP)?;
        self.gpu.submit(|rec| {
            let push = LookupPush {
                tree: self.params(),
                points: points.address(),
                results: results.address(),
                n: n as u32,
                mode,
            };
            rec.dispatch(&kernel, kernel.groups_for(n as u64), &[], &push)
        })?;
        results.read_range(0, n)
    }

    /// A `ctree_sample` lookup at each (uv, lod) kept on the device, run and timed as often as
    /// a benchmark needs (one dispatch between two timestamps).
    pub fn timed_sample(&self, queries: &[Vec4]) -> GpuResult<TimedCtreeLookup<'_>> {
        let flat: Vec<u32> = queries
            .iter()
            .flat_map(|q| q.to_array().map(f32::to_bits))
            .collect();
        Ok(TimedCtreeLookup {
            tree: self,
            points: GpuBuffer::from_slice(&self.gpu, "ctree timed points", &flat)?,
            results: GpuBuffer::zeroed(&self.gpu, "ctree timed results", queries.len().max(1))?,
            n: queries.len(),
            kernel: self.gpu.kernel(&kernels::CTREE_LOOKUP)?,
        })
    }

    /// `ctree_lookup_fixed` at each (position, lod) in fixed point.
    pub fn lookup_fixed(&self, queries: &[UVec4]) -> GpuResult<Vec<i32>> {
        let flat: Vec<u32> = queries.iter().flat_map(|q| q.to_array()).collect();
        let points = GpuBuffer::from_slice(&self.gpu, "ctree lookup points", &flat)?;
        Ok(self
            .run_lookup(points, queries.len(), 0)?
            .into_iter()
            .map(|v| v as i32)
            .collect())
    }

    /// `ctree_sample` at each (uv, lod).
    pub fn sample(&self, queries: &[Vec4]) -> GpuResult<Vec<f32>> {
        let flat: Vec<u32> = queries
            .iter()
            .flat_map(|q| q.to_array().map(f32::to_bits))
            .collect();
        let points = GpuBuffer::from_slice(&self.gpu, "ctree sample points", &flat)?;
        Ok(self
            .run_lookup(points, queries.len(), 1)?
            .into_iter()
            .map(f32::from_bits)
            .collect())
    }
}

/// Lookups of a tree whose points are on the device ([`DeviceTree::timed_sample`]).
pub struct TimedCtreeLookup<'a> {
    tree: &'a DeviceTree,
    points: GpuBuffer<u32>,
    results: GpuBuffer<u32>,
    n: usize,
    kernel: std::sync::Arc<Kernel>,
}

impl TimedCtreeLookup<'_> {
    /// One dispatch; its GPU time in milliseconds.
    pub fn run(&self) -> GpuResult<f64> {
        let push = LookupPush {
            tree: self.tree.params(),
            points: self.points.address(),
            results: self.results.address(),
            n: self.n as u32,
            mode: 1,
        };
        timed_dispatch(&self.tree.gpu, &self.kernel, self.n, &push)
    }

    /// The last run's values.
    pub fn results(&self) -> GpuResult<Vec<f32>> {
        read_floats(&self.results, self.n)
    }
}

/// One dispatch of `kernel` over `n` invocations between two timestamps; its GPU time in
/// milliseconds (the timed lookups of the trees and of the MIP texture they are compared with).
pub(crate) fn timed_dispatch<P: PushBlock>(
    gpu: &Gpu,
    kernel: &Kernel,
    n: usize,
    push: &P,
) -> GpuResult<f64> {
    let ((), t) = gpu.submit_timed(|rec| {
        rec.timestamp()?;
        rec.dispatch(kernel, kernel.groups_for(n as u64), &[], push)?;
        rec.timestamp()
    })?;
    Ok((t[1] - t[0]) * 1e-6)
}

/// The first `n` words of `buffer` as the floats whose bits they hold.
pub(crate) fn read_floats(buffer: &GpuBuffer<u32>, n: usize) -> GpuResult<Vec<f32>> {
    Ok(buffer
        .read_range(0, n)?
        .into_iter()
        .map(f32::from_bits)
        .collect())
}
