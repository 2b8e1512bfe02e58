//! The plain alternative to a compressed tree that benchmarks compare its lookups with: an
//! 8-bit single-channel texture with its MIP pyramid (2×2 box filter), read with trilinear
//! filtering at the same coordinates (`uv` over the texels' centres, clamped) by
//! `glsl/ctree/mip_lookup.comp`, this file being its CPU twin.

use super::device::{read_floats, timed_dispatch};
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Kernel};
use crate::kernels::ctree as kernels;
use glam::Vec4;
use std::sync::Arc;

/// An R8 texture and its pyramid.
#[derive(Clone, Debug)]
pub struct MipTexture {
    /// Per level: width, height and the first texel's index.
    pub levels: Vec<[u32; 3]>,
    /// Every level's texels, rows first.
    pub texels: Vec<u8>,
}

impl MipTexture {
    /// The pyramid of `values` (`width`×`height`, rows first) down to 1×1.
    pub fn new(width: u32, height: u32, values: &[u8]) -> MipTexture {
        let mut levels = vec![[width, height, 0]];
        let mut texels = values.to_vec();
        let (mut w, mut h) = (width, height);
        while w > 1 || h > 1 {
            let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
            let start = levels.last().expect("a level")[2] as usize;
            let at = |x: u32, y: u32| texels[start + (y.min(h - 1) * w + x.min(w - 1)) as usize];
            let mut next = Vec::with_capacity((nw * nh) as usize);
            for y in 0..nh {
                for x in 0..nw {
                    let sum = at(2 * x, 2 * y) as u32
                        + at(2 * x + 1, 2 * y) as u32
                        + at(2 * x, 2 * y + 1) as u32
                        + at(2 * x + 1, 2 * y + 1) as u32;
                    next.push(((sum + 2) / 4) as u8);
                }
            }
            levels.push([nw, nh, texels.len() as u32]);
            texels.extend(next);
            (w, h) = (nw, nh);
        }
        MipTexture { levels, texels }
    }

    fn fetch(&self, l: usize, x: i32, y: i32) -> f32 {
        let [w, h, start] = self.levels[l];
        let x = x.clamp(0, w as i32 - 1) as u32;
        let y = y.clamp(0, h as i32 - 1) as u32;
        self.texels[(start + y * w + x) as usize] as f32
    }

    fn bilinear(&self, l: usize, uv: [f32; 2]) -> f32 {
        let [w, h, _] = self.levels[l];
        let x = uv[0] * w as f32 - 0.5;
        let y = uv[1] * h as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (xi, yi) = (x0 as i32, y0 as i32);
        let a = self.fetch(l, xi, yi) * (1.0 - fx) + self.fetch(l, xi + 1, yi) * fx;
        let b = self.fetch(l, xi, yi + 1) * (1.0 - fx) + self.fetch(l, xi + 1, yi + 1) * fx;
        a * (1.0 - fy) + b * fy
    }

    /// Trilinear lookup at `uv` and level of detail `lod` (clamped to the pyramid).
    pub fn sample(&self, uv: [f32; 2], lod: f32) -> f32 {
        let lod = lod.clamp(0.0, (self.levels.len() - 1) as f32);
        let l0 = lod.floor();
        let f = lod - l0;
        let a = self.bilinear(l0 as usize, uv);
        if f > 0.0 {
            a * (1.0 - f) + self.bilinear(l0 as usize + 1, uv) * f
        } else {
            a
        }
    }

    /// Bytes of the texels (one per texel of every level).
    pub fn bytes(&self) -> u64 {
        self.texels.len() as u64
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MipLookupPush<'a> {
        texels: DeviceAddress<'a>,
        levels: DeviceAddress<'a>,
        points: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        level_count: u32,
        n: u32,
    }
}

/// A MIP texture on the device with lookup points, run and timed as often as needed.
pub struct TimedMipLookup {
    gpu: Gpu,
    texels: GpuBuffer<u32>,
    levels: GpuBuffer<u32>,
    points: GpuBuffer<u32>,
    results: GpuBuffer<u32>,
    level_count: u32,
    n: usize,
    kernel: Arc<Kernel>,
}

impl TimedMipLookup {
    /// Uploads `texture` and the (uv, lod) queries (`x`, `y` and `w` of each).
    pub fn new(gpu: &Gpu, texture: &MipTexture, queries: &[Vec4]) -> GpuResult<TimedMipLookup> {
        let words = super::device::words_of_bytes(&texture.texels);
        let levels: Vec<u32> = texture.levels.iter().flatten().copied().collect();
        let flat: Vec<u32> = queries
            .iter()
            .flat_map(|q| q.to_array().map(f32::to_bits))
            .collect();
        Ok(TimedMipLookup {
            gpu: gpu.clone(),
            texels: GpuBuffer::from_slice(gpu, "mip texels", &words)?,
            levels: GpuBuffer::from_slice(gpu, "mip levels", &levels)?,
            points: GpuBuffer::from_slice(gpu, "mip points", &flat)?,
            results: GpuBuffer::zeroed(gpu, "mip results", queries.len().max(1))?,
            level_count: texture.levels.len() as u32,
            n: queries.len(),
            kernel: gpu.kernel(&kernels::MIP_LOOKUP)?,
        })
    }

    /// One dispatch; its GPU time in milliseconds.
    pub fn run(&self) -> GpuResult<f64> {
        let push = MipLookupPush {
            texels: self.texels.address(),
            levels: self.levels.address(),
            points: self.points.address(),
            results: self.results.address(),
            level_count: self.level_count,
            n: self.n as u32,
        };
        timed_dispatch(&self.gpu, &self.kernel, self.n, &push)
    }

    /// The last run's values.
    pub fn results(&self) -> GpuResult<Vec<f32>> {
        read_floats(&self.results, self.n)
    }
}
