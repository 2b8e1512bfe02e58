//! A scene's baked stores as the path tracer reads them: every store the bake (`crate::bake`)
//! made, one record per store and one store slot per instance; the path tracer reads the store
//! at the hit point instead of evaluating the pattern. One kernel renders every store variant
//! of a scene, which is how the structures are compared in pictures; the records it reads are
//! refreshed after inserts.

use super::error::RenderError;
use crate::bake::{caps_of, Baker, Matter};
use crate::scene::{Scene, StoreFilter};
use crate::shader_constants::{
    STORE_FILTER_NEAREST, STORE_FILTER_TRILINEAR, STORE_KIND_HASH, STORE_KIND_OCTREE,
    STORE_KIND_PERFECT, STORE_KIND_TILETREE,
};
use glam::Vec3;
use lazysolid_compute::gpu::{BufferArg, DeviceRecords, Gpu, GpuBuffer};
use lazysolid_compute::store::{
    ColourSource, Filter, HashStore, HashStoreParams, InsertUnit, OctreeParams, OctreeStore,
    PerfectStore, PerfectStoreParams, SparseStore, StoreError, StoreReport, TileTree,
    TileTreeParams,
};
use lazysolid_compute::voxel::VoxelKeys;
use lazysolid_synth::solid::lazy::MatterStore;
pub use lazysolid_synth::solid::lazy::{CutInfo, SynthesisInfo};
use lazysolid_synth::ExemplarFit;
use std::collections::HashMap;
use std::time::{Duration, Instant};

lazysolid_compute::push_block! {
    /// One store as the kernel sees it (`StoreRecord` in `glsl/render/path_trace.comp`),
    /// borrowing the store: the params of its kind, the others default (null addresses).
    #[derive(Clone, Copy, Debug, Default)]
    pub struct GpuStoreRecord<'a> {
        /// `STORE_KIND_*`.
        pub kind: u32,
        /// `STORE_FILTER_*`.
        pub filter: u32,
        /// Object-space height per unit of the alpha channel of a store with relief (0: no
        /// relief): the path tracer bends shading normals by this times alpha's gradient.
        pub relief: f32,
        /// The coherent-hash store's params.
        pub hash: HashStoreParams<'a>,
        /// The octree's params.
        pub octree: OctreeParams<'a>,
        /// The perfect-hash store's params.
        pub perfect: PerfectStoreParams<'a>,
        /// The TileTree's params.
        pub tiletree: TileTreeParams<'a>,
    }
}

/// How the path tracer reads a store: its filter and its relief.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StoreRead {
    /// Nearest or filtered.
    pub filter: StoreFilter,
    /// Object-space height per unit of alpha (see [`GpuStoreRecord::relief`]).
    pub relief: f32,
}

/// Marks an instance whose albedo is not read from a store; defined with the constants shared
/// with GLSL, which `path_trace.comp` compares the slot with.
pub use crate::shader_constants::NO_STORE;

/// A store a scene baked, of any of the four structures: what callers insert into before
/// [`SceneStores::refresh`].
pub enum SceneStore {
    /// The coherent hash.
    Hash(HashStore),
    /// The N³ tree.
    Octree(OctreeStore),
    /// The perfect hash.
    Perfect(PerfectStore),
    /// The TileTree.
    TileTree(TileTree),
}

impl SceneStore {
    /// The record of the store's current buffers, read as `read` says.
    pub fn record(&self, read: StoreRead) -> GpuStoreRecord<'_> {
        let mut r = GpuStoreRecord {
            filter: match read.filter {
                StoreFilter::Nearest => STORE_FILTER_NEAREST,
                StoreFilter::Trilinear => STORE_FILTER_TRILINEAR,
            },
            relief: read.relief,
            ..Default::default()
        };
        match self {
            SceneStore::Hash(s) => (r.kind, r.hash) = (STORE_KIND_HASH, s.params()),
            SceneStore::Octree(s) => (r.kind, r.octree) = (STORE_KIND_OCTREE, s.params()),
            SceneStore::Perfect(s) => (r.kind, r.perfect) = (STORE_KIND_PERFECT, s.params()),
            SceneStore::TileTree(s) => (r.kind, r.tiletree) = (STORE_KIND_TILETREE, s.params()),
        }
        r
    }
}

/// `$body` with `$s` bound to the store inside `$store`, whatever its kind: the one list of
/// [`SceneStore`]'s variants that every forwarding method shares.
macro_rules! with_store {
    ($store:expr, $s:ident => $body:expr) => {
        match $store {
            SceneStore::Hash($s) => $body,
            SceneStore::Octree($s) => $body,
            SceneStore::Perfect($s) => $body,
            SceneStore::TileTree($s) => $body,
        }
    };
}

/// A scene store forwards to the store of its kind, so matter can grow in any of the four.
impl MatterStore for SceneStore {
    fn insert_unit(&self) -> InsertUnit {
        with_store!(self, s => SparseStore::insert_unit(s))
    }

    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        with_store!(self, s => SparseStore::insert(s, keys, colours))
    }

    fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        with_store!(self, s => SparseStore::insert_surface(s, positions, triangles, colours))
    }

    fn size(&self) -> (u64, u64) {
        with_store!(self, s => (s.len(), s.bytes()))
    }
}

/// Facts about one baked store, for messages.
#[derive(Clone, Debug)]
pub struct BakedStoreInfo {
    /// Mesh name.
    pub mesh: String,
    /// Material name.
    pub material: String,
    /// The scene's name of the structure (`coherent_hash`, `octree`, `perfect_hash`,
    /// `tiletree`).
    pub kind: &'static str,
    /// Voxels per unit.
    pub resolution: u32,
    /// Texels stored.
    pub texels: u64,
    /// Exact GPU bytes.
    pub bytes: u64,
    /// Voxelization and fill time (with the synthesis, for a synthesized texture).
    pub build_time: Duration,
    /// For a synthesized texture: how its image became the exemplar.
    pub exemplar: Option<ExemplarFit>,
    /// For a synthesized texture: what its lazy synthesis did.
    pub synthesis: Option<SynthesisInfo>,
    /// For the texture of cut or fractured pieces: what adding their cap faces did.
    pub cut: Option<CutInfo>,
}

/// Every store of a scene, the records the kernel reads (which hold the buffers they point
/// into) and the per-instance store slots. After an insert into a store
/// ([`SceneStores::store_mut`]), which may reallocate its buffers, [`SceneStores::refresh`]
/// rewrites the records before the next render (until then they keep the old buffers alive).
pub struct SceneStores {
    gpu: Gpu,
    stores: Vec<(Matter, StoreRead)>,
    records: DeviceRecords,
    instance_slots: GpuBuffer<u32>,
    /// `instance_slots` on the host, for readers outside the kernel (the export's bake).
    slots: Vec<u32>,
    info: Vec<BakedStoreInfo>,
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
        let mut baker = Baker::new(gpu);
        for (i, inst) in scene.instances.iter().enumerate() {
            let material = &scene.materials[inst.material];
            let Some(spec) = material.texture.as_ref().and_then(|t| t.store) else {
                continue;
            };
            // Pieces share the store of the mesh they were cut from: same coordinates, same
            // matter, one store holding the outer surface and every cap.
            let root = scene.meshes[inst.mesh]
                .cut_from
                .as_ref()
                .map_or(inst.mesh, |(m, _)| *m);
            if let Some(&slot) = slot_of.get(&(root, inst.material)) {
                slots[i] = slot;
                continue;
            }
            let caps = caps_of(scene, root, inst.material);
            let start = Instant::now();
            let (matter, synthesis, cut, relief) = baker.bake(
                scene,
                root,
                inst.material,
                caps.as_ref().map(|(p, t)| (&p[..], &t[..])),
            )?;
            let (texels, bytes) = matter.store().size();
            info.push(BakedStoreInfo {
                mesh: scene.meshes[root].name.clone(),
                material: material.name.clone(),
                kind: spec.kind.name(),
                resolution: spec.resolution,
                texels,
                bytes,
                build_time: start.elapsed(),
                exemplar: material
                    .texture
                    .as_ref()
                    .and_then(|t| t.synthesized.as_ref())
                    .map(|s| s.fit.clone()),
                synthesis,
                cut,
            });
            let slot = stores.len() as u32;
            stores.push((
                matter,
                StoreRead {
                    filter: spec.filter,
                    relief,
                },
            ));
            slot_of.insert((root, inst.material), slot);
            slots[i] = slot;
        }
        let records = Self::upload(gpu, &stores)?;
        Ok(SceneStores {
            gpu: gpu.clone(),
            stores,
            records,
            instance_slots: GpuBuffer::from_slice(gpu, "render instance stores", &slots)?,
            slots,
            info,
        })
    }

    /// The store of `slot` (in the order of [`SceneStores::info`]), to insert texels into;
    /// call [`SceneStores::refresh`] before the next render.
    pub fn store_mut(&mut self, slot: usize) -> Option<&mut SceneStore> {
        self.stores.get_mut(slot).map(|(m, _)| m.store_mut())
    }

    /// The records of `stores` on the device (one default record when there is no store:
    /// bindings cannot be empty).
    fn upload(gpu: &Gpu, stores: &[(Matter, StoreRead)]) -> Result<DeviceRecords, RenderError> {
        let mut records: Vec<GpuStoreRecord<'_>> =
            stores.iter().map(|(m, f)| m.store().record(*f)).collect();
        if records.is_empty() {
            records.push(GpuStoreRecord::default());
        }
        Ok(DeviceRecords::new(gpu, "render store records", &records)?)
    }

    /// The record of every store as the kernel reads it after the next
    /// [`SceneStores::refresh`] (or now, when no store changed since the last).
    pub fn records(&self) -> Vec<GpuStoreRecord<'_>> {
        self.stores
            .iter()
            .map(|(m, f)| m.store().record(*f))
            .collect()
    }

    /// One bit per `STORE_KIND_*` the scene's stores use: the path tracer compiles only those
    /// lookups.
    pub fn kinds_mask(&self) -> u32 {
        super::kinds_mask(self.records().iter().map(|r| r.kind))
    }

    /// Rewrites the kernel's records from the stores' current buffers (after inserts, which
    /// may have reallocated them) and their sizes in [`SceneStores::info`].
    ///
    /// # Errors
    /// Device failures.
    pub fn refresh(&mut self) -> Result<(), RenderError> {
        self.records = Self::upload(&self.gpu, &self.stores)?;
        for ((matter, _), info) in self.stores.iter().zip(&mut self.info) {
            (info.texels, info.bytes) = matter.store().size();
        }
        Ok(())
    }

    /// The bindings of `path_trace.comp` that describe the stores.
    pub fn bindings(&self) -> [(&'static str, BufferArg<'_>); 2] {
        [
            ("StoreRecords", self.records.arg()),
            ("InstanceStores", self.instance_slots.arg()),
        ]
    }

    /// The store slot instance `instance` reads, `None` when its material has no store.
    #[must_use]
    pub fn slot_of(&self, instance: usize) -> Option<usize> {
        self.slots
            .get(instance)
            .filter(|&&s| s != NO_STORE)
            .map(|&s| s as usize)
    }

    /// The colour the path tracer's `store_albedo` reads from store `slot` at object-space
    /// surface points with their object-space geometric normals, before it decodes sRGB: the
    /// filtered colour divided by its weight (the sample lookup's coverage for a store whose
    /// alpha carries relief), through the same GLSL lookups. `None` where nothing is stored
    /// (the tracer shows magenta there). How an export bakes the matter into images.
    ///
    /// # Errors
    /// No such slot, or a device failure.
    pub fn albedo_srgb(
        &self,
        slot: usize,
        points: &[Vec3],
        normals: &[Vec3],
    ) -> Result<Vec<Option<Vec3>>, RenderError> {
        let (matter, read) = self
            .stores
            .get(slot)
            .ok_or_else(|| RenderError::Settings(format!("no store in slot {slot}")))?;
        let store = matter.store();
        let failed = |e: StoreError| RenderError::Settings(format!("store lookup: {e}"));
        if read.relief > 0.0 {
            let samples =
                with_store!(store, s => s.sample_lookup(points, normals)).map_err(failed)?;
            Ok(samples
                .iter()
                .map(|s| (s.coverage > 0.0).then(|| s.sum.truncate() / s.coverage))
                .collect())
        } else {
            let filter = match read.filter {
                StoreFilter::Nearest => Filter::Nearest,
                StoreFilter::Trilinear => Filter::Trilinear,
            };
            let colours = with_store!(store, s => s.lookup_with_normals(points, normals, filter))
                .map_err(failed)?;
            Ok(colours
                .iter()
                .map(|c| (c.w > 0.0).then(|| c.truncate() / c.w))
                .collect())
        }
    }

    /// What was baked.
    pub fn info(&self) -> &[BakedStoreInfo] {
        &self.info
    }
}
