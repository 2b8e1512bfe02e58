//! The device record of an infinite normal map by example (`GlintMap` in
//! `glsl/include/glint/by_example.glsl`) and the buffers it points at.

use super::by_example::ByExampleMap;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult};

lazysolid_compute::push_block! {
    /// The GLSL `GlintMap` record.
    #[derive(Clone, Copy, Default)]
    pub struct GlintMapParams<'a> {
        /// size² texels of (n_x, n_y), row by row.
        pub texels: DeviceAddress<'a>,
        /// G_x, G_y, G⁻¹_x, G⁻¹_y, `GLINT_TABLE_KNOTS` floats each.
        pub tables: DeviceAddress<'a>,
        /// Example edge in texels.
        pub size: u32,
        /// Target patch edge l in texels.
        pub patch_edge: u32,
        /// Hash seed of the vertex origins.
        pub seed: u32,
        /// `GLINT_BLEND_*`.
        pub mode: u32,
        /// Domain start of G per component.
        pub forward_lo: [f32; 2],
        /// Domain end of G per component.
        pub forward_hi: [f32; 2],
        /// Domain of G⁻¹: [−inverse_max, inverse_max] (both components).
        pub inverse_max: f32,
        /// Example mean μ (variance-preserving blending).
        pub mean: [f32; 2],
    }
}

/// A map uploaded to the device: owns the buffers its [`GlintMapParams`] point at.
pub struct GpuGlintMap {
    texels: GpuBuffer<[f32; 2]>,
    tables: GpuBuffer<f32>,
    constants: GlintMapParams<'static>,
}

impl GpuGlintMap {
    /// Uploads `map`'s example and tables.
    ///
    /// # Errors
    /// Allocation and upload errors.
    pub fn new(gpu: &Gpu, map: &ByExampleMap) -> GpuResult<Self> {
        let texels: Vec<[f32; 2]> = map
            .example()
            .texels()
            .iter()
            .map(|n| n.to_array())
            .collect();
        let texels = GpuBuffer::from_slice(gpu, "glint example texels", &texels)?;
        let tables = GpuBuffer::from_slice(gpu, "glint tables", &map.tables().device_knots())?;
        let t = map.tables();
        let constants = GlintMapParams {
            size: map.example().size() as u32,
            patch_edge: map.patch(),
            seed: map.seed(),
            mode: map.mode().code(),
            forward_lo: [t.forward[0].lo, t.forward[1].lo],
            forward_hi: [t.forward[0].hi, t.forward[1].hi],
            inverse_max: t.inverse[0].hi,
            mean: map.mean().to_array(),
            ..Default::default()
        };
        Ok(GpuGlintMap {
            texels,
            tables,
            constants,
        })
    }

    /// The GLSL record, to copy into push constants or device records.
    pub fn params(&self) -> GlintMapParams<'_> {
        GlintMapParams {
            texels: self.texels.address(),
            tables: self.tables.address(),
            ..self.constants
        }
    }
}
