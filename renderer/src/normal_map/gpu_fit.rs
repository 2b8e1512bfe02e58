//! The vMF pyramid fitted on the device: per level, [`MAX_EM_ITERATIONS`] rounds of
//! `glsl/render/vmf_em_accumulate.comp` (the E-step over chunks of each texel's covered normals)
//! and `vmf_em_update.comp` (the M-step and the stopping test), in f32; each level's start
//! (the children's farthest lobes, [`level_start`]) is chosen on the host between levels. The
//! CPU fit ([`VmfPyramid::build`], f64) is its reference.

use super::mixture::{EM_TOLERANCE, MAX_EM_ITERATIONS};
use super::pyramid::{
    finest_level, level_start, map_normals, VmfLevel, VmfPyramid, LOBES_PER_TEXEL,
};
use super::vmf::VmfLobe;
use crate::glint::NormalExample;
use crate::kernels::render::{VMF_EM_ACCUMULATE, VMF_EM_UPDATE};
use crate::shader_constants::VMF_EM_CHUNK;
use glam::DVec3;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult};
use rayon::prelude::*;

lazysolid_compute::push_block! {
    /// Push block of `glsl/render/vmf_em_accumulate.comp`.
    #[derive(Clone, Copy)]
    pub struct VmfEmAccumulatePush<'a> {
        pub normals: DeviceAddress<'a>,
        pub lobes: DeviceAddress<'a>,
        pub partials: DeviceAddress<'a>,
        pub likelihoods: DeviceAddress<'a>,
        pub states: DeviceAddress<'a>,
        pub size: u32,
        pub edge: u32,
        pub span: u32,
        pub chunks: u32,
        pub lobe_count: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render/vmf_em_update.comp`.
    #[derive(Clone, Copy)]
    pub struct VmfEmUpdatePush<'a> {
        pub lobes: DeviceAddress<'a>,
        pub partials: DeviceAddress<'a>,
        pub likelihoods: DeviceAddress<'a>,
        pub states: DeviceAddress<'a>,
        pub edge: u32,
        pub chunks: u32,
        pub lobe_count: u32,
        pub total: f32,
        pub tolerance: f32,
    }
}

/// A device-ready level: the level's `edge`, and its lobes as the kernels store them.
fn to_device(lobes: &[VmfLobe]) -> Vec<[f32; 5]> {
    lobes
        .iter()
        .map(|l| {
            [
                l.mu.x as f32,
                l.mu.y as f32,
                l.mu.z as f32,
                l.kappa as f32,
                l.alpha as f32,
            ]
        })
        .collect()
}

fn from_device(lobes: &[[f32; 5]]) -> Vec<VmfLobe> {
    lobes
        .iter()
        .map(|l| VmfLobe {
            alpha: f64::from(l[4]),
            mu: DVec3::new(f64::from(l[0]), f64::from(l[1]), f64::from(l[2])),
            kappa: f64::from(l[3]),
        })
        .collect()
}

/// The device's buffers for one map: its normals, reused by every level (and kept on the
/// host for the finest level and the starts).
pub struct GpuVmfFitter {
    gpu: Gpu,
    size: usize,
    host_normals: Vec<DVec3>,
    normals: GpuBuffer<[f32; 4]>,
}

impl GpuVmfFitter {
    /// Uploads `map`'s unit normals.
    ///
    /// # Errors
    /// Allocation and upload errors.
    pub fn new(gpu: &Gpu, map: &NormalExample) -> GpuResult<GpuVmfFitter> {
        let host_normals = map_normals(map);
        let normals: Vec<[f32; 4]> = host_normals
            .iter()
            .map(|n| [n.x as f32, n.y as f32, n.z as f32, 0.0])
            .collect();
        Ok(GpuVmfFitter {
            gpu: gpu.clone(),
            size: map.size(),
            host_normals,
            normals: GpuBuffer::from_slice(gpu, "vmf normals", &normals)?,
        })
    }

    /// Fits the level of edge `edge` from the starts `init` (`edge² · j` lobes, texel by texel)
    /// on the device and reads it back.
    ///
    /// # Errors
    /// Device errors; [`GpuError::InvalidArgument`] for an edge that does not divide the map
    /// or a start of the wrong length.
    pub fn fit_level(&self, edge: usize, j: usize, init: &[VmfLobe]) -> GpuResult<VmfLevel> {
        if edge == 0 || self.size % edge != 0 || init.len() != edge * edge * j {
            return Err(GpuError::InvalidArgument(format!(
                "vMF level of edge {edge} with {j} lobes over a {0}² map: {1} starts given",
                self.size,
                init.len()
            )));
        }
        let span = self.size / edge;
        let covered = span * span;
        let chunks = covered.div_ceil(VMF_EM_CHUNK as usize);
        let texels = edge * edge;
        let gpu = &self.gpu;
        let lobes = GpuBuffer::from_slice(gpu, "vmf lobes", &to_device(init))?;
        let partials = GpuBuffer::<[f32; 4]>::zeroed(gpu, "vmf partials", texels * chunks * j)?;
        let likelihoods = GpuBuffer::<f32>::zeroed(gpu, "vmf likelihoods", texels * chunks)?;
        let states = GpuBuffer::<[u32; 4]>::zeroed(gpu, "vmf states", texels)?;
        let accumulate = gpu.kernel(&VMF_EM_ACCUMULATE)?;
        let update = gpu.kernel(&VMF_EM_UPDATE)?;
        let a = VmfEmAccumulatePush {
            normals: self.normals.address(),
            lobes: lobes.address(),
            partials: partials.address(),
            likelihoods: likelihoods.address(),
            states: states.address(),
            size: self.size as u32,
            edge: edge as u32,
            span: span as u32,
            chunks: chunks as u32,
            lobe_count: j as u32,
        };
        let u = VmfEmUpdatePush {
            lobes: lobes.address(),
            partials: partials.address(),
            likelihoods: likelihoods.address(),
            states: states.address(),
            edge: edge as u32,
            chunks: chunks as u32,
            lobe_count: j as u32,
            total: covered as f32,
            tolerance: EM_TOLERANCE as f32,
        };
        gpu.submit(|rec| {
            for _ in 0..MAX_EM_ITERATIONS {
                rec.dispatch(
                    &accumulate,
                    accumulate.groups_for((texels * chunks) as u64),
                    &[],
                    &a,
                )?;
                rec.barrier();
                rec.dispatch(&update, update.groups_for(texels as u64), &[], &u)?;
                rec.barrier();
            }
            Ok(())
        })?;
        Ok(VmfLevel {
            size: edge,
            lobes: from_device(&lobes.read()?),
        })
    }

    /// Every level, the finest (one sharp lobe per texel, as on the CPU) first.
    ///
    /// # Errors
    /// Device errors; a lobe count outside [`LOBES_PER_TEXEL`] as [`GpuError::InvalidArgument`].
    pub fn build(&self, j: usize) -> GpuResult<VmfPyramid> {
        if !LOBES_PER_TEXEL.contains(&j) {
            return Err(GpuError::InvalidArgument(format!(
                "lobes per texel is {j}; it must lie in {}..={}",
                LOBES_PER_TEXEL.start(),
                LOBES_PER_TEXEL.end()
            )));
        }
        let mut levels = vec![finest_level(&self.host_normals, self.size, j)];
        while levels.last().expect("one level").size > 1 {
            let child = levels.last().expect("one level");
            let edge = child.size / 2;
            let init: Vec<VmfLobe> = (0..edge * edge)
                .into_par_iter()
                .flat_map_iter(|t| level_start(child, j, t % edge, t / edge))
                .collect();
            levels.push(self.fit_level(edge, j, &init)?);
        }
        Ok(VmfPyramid {
            lobes_per_texel: j,
            levels,
        })
    }
}
