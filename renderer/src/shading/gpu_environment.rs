//! The environment on the device: its tables in buffers, and the record
//! (`Environment` in `glsl/include/render/environment.glsl`) that points at them.

use super::environment_map::EnvironmentMap;
use super::error::ShadingError;
use crate::scene::Environment;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult};

lazysolid_compute::push_block! {
/// The GLSL `Environment` record: constants plus the device addresses of the tables. Kernels
/// receive it in a buffer or in push constants; it borrows its [`GpuEnvironment`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnvironmentParams<'a> {
    /// Radiance of a constant environment.
    pub radiance: [f32; 3],
    /// `ENVIRONMENT_*` of `shader_constants`.
    pub kind: u32,
    /// Multiplier of the map's texels.
    pub intensity: f32,
    /// cos of the rotation about +y.
    pub rotation_cos: f32,
    /// sin of the rotation about +y.
    pub rotation_sin: f32,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// 0 when nothing can be sampled.
    pub sampleable: u32,
    /// Address of the RGB texels.
    pub texels: DeviceAddress<'a>,
    /// Address of the per-texel density.
    pub pdf: DeviceAddress<'a>,
    /// Address of the marginal CDF.
    pub marginal_cdf: DeviceAddress<'a>,
    /// Address of the conditional CDFs.
    pub conditional_cdf: DeviceAddress<'a>,
}
}

/// An environment uploaded to the device: owns the buffers its [`EnvironmentParams`] point at.
pub struct GpuEnvironment {
    texels: GpuBuffer<f32>,
    pdf: GpuBuffer<f32>,
    marginal_cdf: GpuBuffer<f32>,
    conditional_cdf: GpuBuffer<f32>,
    /// The record's constants (its addresses are null here; see [`GpuEnvironment::params`]).
    constants: EnvironmentParams<'static>,
}

impl GpuEnvironment {
    /// Uploads `map`'s tables.
    pub fn new(gpu: &Gpu, map: &EnvironmentMap) -> GpuResult<Self> {
        let texels = GpuBuffer::from_slice(gpu, "environment texels", &map.texels)?;
        let pdf = GpuBuffer::from_slice(gpu, "environment pdf", &map.pdf)?;
        let marginal_cdf =
            GpuBuffer::from_slice(gpu, "environment marginal cdf", &map.marginal_cdf)?;
        let conditional_cdf =
            GpuBuffer::from_slice(gpu, "environment conditional cdf", &map.conditional_cdf)?;
        let constants = EnvironmentParams {
            radiance: map.radiance.to_array(),
            kind: map.kind,
            intensity: map.intensity,
            rotation_cos: map.rotation_cos,
            rotation_sin: map.rotation_sin,
            width: map.width,
            height: map.height,
            sampleable: map.sampleable as u32,
            ..Default::default()
        };
        Ok(GpuEnvironment {
            texels,
            pdf,
            marginal_cdf,
            conditional_cdf,
            constants,
        })
    }

    /// Loads the scene's environment (the EXR of a lat-long map) and uploads it.
    ///
    /// # Errors
    /// Those of [`EnvironmentMap::from_scene`], and device errors naming the map's file.
    pub fn from_scene(gpu: &Gpu, environment: &Environment) -> Result<Self, ShadingError> {
        let map = EnvironmentMap::from_scene(environment)?;
        Self::new(gpu, &map).map_err(|source| ShadingError::Gpu {
            file: map.source.clone(),
            source,
        })
    }

    /// The GLSL record, to copy into device records or push constants.
    pub fn params(&self) -> EnvironmentParams<'_> {
        EnvironmentParams {
            texels: self.texels.address(),
            pdf: self.pdf.address(),
            marginal_cdf: self.marginal_cdf.address(),
            conditional_cdf: self.conditional_cdf.address(),
            ..self.constants
        }
    }

    /// Device bytes of the tables.
    pub fn bytes(&self) -> u64 {
        self.texels.bytes()
            + self.pdf.bytes()
            + self.marginal_cdf.bytes()
            + self.conditional_cdf.bytes()
    }
}
