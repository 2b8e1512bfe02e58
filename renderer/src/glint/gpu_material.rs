//! The device records of a scene's glint materials (`GlintRecord` in
//! `glsl/include/render/glint_bsdf.glsl`): each material's example, Gaussianization tables and
//! range table are uploaded (the table built on the device) once, when the path tracer is made.

use super::gpu_map::{GlintMapParams, GpuGlintMap};
use super::gpu_range_table::build_range_table;
use crate::scene::{GlintProjection, GlintSpec, Scene};
use crate::shader_constants::{GLINT_NONE, GLINT_UV_MESH, GLINT_UV_PLANAR, GLINT_UV_SPHERICAL};
use lazysolid_compute::gpu::{DeviceAddress, DeviceRecords, Gpu, GpuResult};

/// Largest footprint width σ_P in texels: wider pixel cones are left to pixel sampling (the
/// footprint box then holds at most (6 σ_P + 1)² = 169 texels).
pub const MAX_FOOTPRINT_TEXELS: f32 = 2.0;

lazysolid_compute::push_block! {
    /// The GLSL `GlintRecord`.
    #[derive(Clone, Copy, Default)]
    pub struct GlintRecordParams<'a> {
        /// The infinite normal map.
        pub map: GlintMapParams<'a>,
        /// Its range table (levels × size² packed entries).
        pub ranges: DeviceAddress<'a>,
        /// Levels of the table.
        pub levels: u32,
        /// Intrinsic roughness σ_r.
        pub sigma_r: f32,
        /// Example texels per scene unit.
        pub texels_per_unit: f32,
        /// `GLINT_UV_*`.
        pub projection: u32,
        /// 1: pruned traversal; 0: every texel of the footprint (the explicit reference).
        pub prune: u32,
        /// GGX α of the shadowing term.
        pub shadow_alpha: f32,
        /// Largest σ_P in texels.
        pub max_footprint: f32,
    }
}

/// The glint records of a scene and the record index of each material (`GLINT_NONE` for
/// materials without a microstructure).
pub struct SceneGlints {
    /// One record per glint material (one unused record when there are none: a binding
    /// cannot be empty).
    pub records: DeviceRecords,
    /// Per scene material, its record.
    pub slots: Vec<u32>,
    /// Device bytes of the examples, tables and range tables.
    pub bytes: u64,
}

impl SceneGlints {
    /// Uploads every glint material of `scene`.
    ///
    /// # Errors
    /// Allocation, upload and dispatch errors.
    pub fn build(gpu: &Gpu, scene: &Scene) -> GpuResult<Self> {
        let mut maps = Vec::new();
        let mut slots = Vec::with_capacity(scene.materials.len());
        let mut bytes = 0u64;
        for m in &scene.materials {
            match &m.glint {
                Some(spec) => {
                    slots.push(maps.len() as u32);
                    let map = GpuGlintMap::new(gpu, &spec.map)?;
                    let table = build_range_table(gpu, spec.map.example(), spec.map.patch())?;
                    let size = spec.map.example().size() as u64;
                    bytes += table.bytes() + size * size * 8 + 4 * 256 * 4;
                    maps.push((spec, map, table));
                }
                None => slots.push(GLINT_NONE),
            }
        }
        let records: Vec<GlintRecordParams> = maps
            .iter()
            .map(|(spec, map, table)| record(spec, map.params(), table.address()))
            .collect();
        let records = if records.is_empty() {
            DeviceRecords::new(gpu, "glint records", &[GlintRecordParams::default()])?
        } else {
            DeviceRecords::new(gpu, "glint records", &records)?
        };
        Ok(SceneGlints {
            records,
            slots,
            bytes,
        })
    }
}

fn record<'a>(
    spec: &GlintSpec,
    map: GlintMapParams<'a>,
    ranges: DeviceAddress<'a>,
) -> GlintRecordParams<'a> {
    GlintRecordParams {
        map,
        ranges,
        levels: spec.map.patch().trailing_zeros() + 1,
        sigma_r: spec.intrinsic_roughness,
        texels_per_unit: spec.map.example().size() as f32 / spec.scale,
        projection: match spec.projection {
            GlintProjection::Planar => GLINT_UV_PLANAR,
            GlintProjection::Spherical => GLINT_UV_SPHERICAL,
            GlintProjection::Mesh => GLINT_UV_MESH,
        },
        prune: (!spec.explicit) as u32,
        shadow_alpha: spec.shadow_alpha,
        max_footprint: MAX_FOOTPRINT_TEXELS,
    }
}
