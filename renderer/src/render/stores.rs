//! Solid textures baked into sparse stores: for every (mesh, material) pair whose texture asks
//! for a store, the mesh's surface voxels (or interpolation voxels, for trilinear reads) are
//! filled with the texture's colour at each voxel centre, and the path tracer reads the store
//! at the hit point instead of evaluating the pattern. One kernel renders every store variant of
//! a scene, which is how the structures are compared in pictures.

use super::error::RenderError;
use crate::output::encode8;
use crate::scene::{Scene, StoreFilter, StoreKind};
use crate::shader_constants::{
    STORE_FILTER_NEAREST, STORE_FILTER_TRILINEAR, STORE_KIND_HASH, STORE_KIND_OCTREE,
};
use crate::shading::reference::solid_texture_albedo;
use crate::shading::GpuMaterial;
use glam::Vec3;
use lazysolid_compute::gpu::{BufferArg, DeviceRecords, Gpu, GpuBuffer};
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, HashStore, HashStoreParams, OctreeConfig, OctreeParams, OctreeStore, SparseStore,
    StoreKernels,
};
use lazysolid_compute::voxel::Voxelizer;
use std::collections::HashMap;
use std::time::{Duration, Instant};

lazysolid_compute::push_block! {
    /// One store as the kernel sees it (`StoreRecord` in `glsl/render/path_trace.comp`),
    /// borrowing the store.
    #[derive(Clone, Copy, Debug, Default)]
    pub struct GpuStoreRecord<'a> {
        /// `STORE_KIND_*`.
        pub kind: u32,
        /// `STORE_FILTER_*`.
        pub filter: u32,
        /// The hash store's params (default for an octree).
        pub hash: HashStoreParams<'a>,
        /// The octree's params (default for a hash).
        pub octree: OctreeParams<'a>,
    }
}

/// Marks an instance whose albedo is not read from a store.
pub const NO_STORE: u32 = u32::MAX;

/// Facts about one baked store, for messages.
#[derive(Clone, Debug)]
pub struct BakedStoreInfo {
    /// Mesh name.
    pub mesh: String,
    /// Material name.
    pub material: String,
    /// `coherent_hash` or `octree`.
    pub kind: &'static str,
    /// Voxels per unit.
    pub resolution: u32,
    /// Texels stored.
    pub texels: u64,
    /// Exact GPU bytes.
    pub bytes: u64,
    /// Voxelization and fill time.
    pub build_time: Duration,
}

enum Baked {
    Hash(HashStore),
    Octree(OctreeStore),
}

/// The records of every store of a scene (which hold the stores' buffers) and the
/// per-instance store slots.
pub struct SceneStores {
    records: DeviceRecords,
    instance_slots: GpuBuffer<u32>,
    info: Vec<BakedStoreInfo>,
}

/// sRGB-encoded RGBA8 (alpha 255) of a linear albedo: 8 bits per channel spent where the eye
/// sees differences, decoded in the kernel.
fn pack_srgb8(albedo: Vec3) -> u32 {
    let [r, g, b] = albedo.to_array().map(|v| encode8(v) as u32);
    r | g << 8 | b << 16 | 255 << 24
}

impl SceneStores {
    /// Bakes the stores `scene`'s materials ask for.
    ///
    /// # Errors
    /// Voxelization or store failures (a mesh outside the unit cube, device limits).
    pub fn build(gpu: &Gpu, scene: &Scene) -> Result<SceneStores, RenderError> {
        let mut stores = Vec::new();
        let mut info = Vec::new();
        let mut slot_of: HashMap<(usize, usize), u32> = HashMap::new();
        let mut slots = vec![NO_STORE; scene.instances.len()];
        let mut kernels = None;
        let mut voxelizer = None;
        for (i, inst) in scene.instances.iter().enumerate() {
            let material = &scene.materials[inst.material];
            let Some(spec) = material.texture.and_then(|t| t.store) else {
                continue;
            };
            if let Some(&slot) = slot_of.get(&(inst.mesh, inst.material)) {
                slots[i] = slot;
                continue;
            }
            let start = Instant::now();
            let kernels = match &kernels {
                Some(k) => k,
                None => kernels.insert(StoreKernels::new(gpu)?),
            };
            let voxelizer = match &mut voxelizer {
                Some(v) => v,
                None => voxelizer.insert(Voxelizer::new(gpu).map_err(store_error)?),
            };
            let mesh = &scene.meshes[inst.mesh];
            let r = spec.resolution;
            let keys = match spec.filter {
                StoreFilter::Nearest => {
                    voxelizer.surface(&mesh.mesh.positions, &mesh.mesh.triangles, r)
                }
                StoreFilter::Trilinear => {
                    voxelizer.interpolation(&mesh.mesh.positions, &mesh.mesh.triangles, r)
                }
            }
            .map_err(|e| {
                RenderError::Settings(format!(
                    "{}: baking material {:?} on mesh {:?}: {e}",
                    scene.source.display(),
                    material.name,
                    mesh.name
                ))
            })?;
            let gm = GpuMaterial::from(material);
            let colour = move |v: [u32; 3]| {
                let centre = (Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32) + 0.5) / r as f32;
                pack_srgb8(solid_texture_albedo(&gm, centre))
            };
            let source = ColourSource::Fn(&colour);
            let filter = match spec.filter {
                StoreFilter::Nearest => STORE_FILTER_NEAREST,
                StoreFilter::Trilinear => STORE_FILTER_TRILINEAR,
            };
            let baked = match spec.kind {
                StoreKind::CoherentHash => Baked::Hash(
                    HashStore::build(kernels, r, &keys, &source, RobinHoodConfig::default())
                        .map_err(store_error)?,
                ),
                StoreKind::Octree => {
                    let config = OctreeConfig::for_resolution(r).map_err(store_error)?;
                    let (s, _) = OctreeStore::build(kernels, r, &keys, &source, config)
                        .map_err(store_error)?;
                    Baked::Octree(s)
                }
            };
            let (kind, texels, bytes) = match &baked {
                Baked::Hash(s) => ("coherent_hash", s.len(), s.bytes()),
                Baked::Octree(s) => ("octree", s.len(), s.bytes()),
            };
            info.push(BakedStoreInfo {
                mesh: mesh.name.clone(),
                material: material.name.clone(),
                kind,
                resolution: r,
                texels,
                bytes,
                build_time: start.elapsed(),
            });
            let slot = stores.len() as u32;
            stores.push((baked, filter));
            slot_of.insert((inst.mesh, inst.material), slot);
            slots[i] = slot;
        }
        let mut records: Vec<GpuStoreRecord<'_>> = stores
            .iter()
            .map(|(baked, filter)| match baked {
                Baked::Hash(s) => GpuStoreRecord {
                    kind: STORE_KIND_HASH,
                    filter: *filter,
                    hash: s.params(),
                    ..Default::default()
                },
                Baked::Octree(s) => GpuStoreRecord {
                    kind: STORE_KIND_OCTREE,
                    filter: *filter,
                    octree: s.params(),
                    ..Default::default()
                },
            })
            .collect();
        if records.is_empty() {
            // Bindings cannot be empty.
            records.push(GpuStoreRecord::default());
        }
        // The records hold the buffers of the stores they point into, so the stores
        // themselves need not outlive this function.
        Ok(SceneStores {
            records: DeviceRecords::new(gpu, "render store records", &records)?,
            instance_slots: GpuBuffer::from_slice(gpu, "render instance stores", &slots)?,
            info,
        })
    }

    /// The bindings of `path_trace.comp` that describe the stores.
    pub fn bindings(&self) -> [(&'static str, BufferArg<'_>); 2] {
        [
            ("StoreRecords", self.records.arg()),
            ("InstanceStores", self.instance_slots.arg()),
        ]
    }

    /// What was baked.
    pub fn info(&self) -> &[BakedStoreInfo] {
        &self.info
    }
}

fn store_error(e: impl std::fmt::Display) -> RenderError {
    RenderError::Settings(format!("sparse store: {e}"))
}
