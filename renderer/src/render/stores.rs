//! Solid textures baked into sparse stores: for every (mesh, material) pair whose texture asks
//! for a store, the mesh's surface voxels (or interpolation voxels, for trilinear reads) are
//! filled with the texture's colour at each voxel centre — or, for the TileTree, the texels of
//! tiles built from the mesh itself — and the path tracer reads the store at the hit point
//! instead of evaluating the pattern. One kernel renders every store variant of a scene, which
//! is how the structures are compared in pictures; the records it reads are refreshed after
//! inserts.

use super::error::RenderError;
use crate::output::encode8;
use crate::scene::{Scene, StoreFilter, StoreKind, StoreSpec, SynthesizedSpec};
use crate::shader_constants::{
    STORE_FILTER_NEAREST, STORE_FILTER_TRILINEAR, STORE_KIND_HASH, STORE_KIND_OCTREE,
    STORE_KIND_PERFECT, STORE_KIND_TILETREE,
};
use crate::shading::reference::solid_texture_albedo;
use crate::shading::GpuMaterial;
use glam::Vec3;
use lazysolid_compute::gpu::{BufferArg, DeviceRecords, Gpu, GpuBuffer};
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, HashStore, HashStoreParams, OctreeConfig, OctreeParams, OctreeStore,
    PerfectStore, PerfectStoreParams, SparseStore, StoreKernels, TileTree, TileTreeConfig,
    TileTreeParams,
};
use lazysolid_compute::voxel::{VoxelKeys, Voxelizer};
use lazysolid_synth::cache::DiskCache;
use lazysolid_synth::solid::lazy::GpuLazySolid;
use lazysolid_synth::solid::SolidExemplars;
use lazysolid_synth::{load_solid, ExemplarFit, FitMode, SynthError};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;
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

/// Marks an instance whose albedo is not read from a store.
pub const NO_STORE: u32 = u32::MAX;

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
    /// The record of the store's current buffers, read with `filter`.
    pub fn record(&self, filter: StoreFilter) -> GpuStoreRecord<'_> {
        let mut r = GpuStoreRecord {
            filter: match filter {
                StoreFilter::Nearest => STORE_FILTER_NEAREST,
                StoreFilter::Trilinear => STORE_FILTER_TRILINEAR,
            },
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

    /// Texels stored and exact GPU bytes.
    pub fn size(&self) -> (u64, u64) {
        match self {
            SceneStore::Hash(s) => (s.len(), s.bytes()),
            SceneStore::Octree(s) => (s.len(), s.bytes()),
            SceneStore::Perfect(s) => (s.len(), s.bytes()),
            SceneStore::TileTree(s) => (s.len(), s.bytes()),
        }
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
    stores: Vec<(SceneStore, StoreFilter)>,
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

/// What one lazy synthesis request did.
#[derive(Clone, Copy, Debug)]
pub struct SynthesisInfo {
    /// Voxel versions computed over all levels (upsampled or corrected).
    pub versions: u64,
    /// Voxels the request needed at the finest level.
    pub finest: u64,
    /// Bytes of the kept synthesis state of the texture (shared by its stores), after it.
    pub state_bytes: u64,
    /// Wall time of the request.
    pub time: Duration,
}

/// What adding the cap faces of cut or fractured pieces to a store did.
#[derive(Clone, Copy, Debug)]
pub struct CutInfo {
    /// Cap triangles over all pieces.
    pub cap_triangles: u64,
    /// Voxels the caps need (surface or interpolation voxels).
    pub requested_voxels: u64,
    /// Of those, voxels the store did not hold (for a TileTree: the voxels its colour buffer
    /// covers, outer and cap).
    pub new_voxels: u64,
    /// The lazy synthesis of those voxels, for a synthesized texture.
    pub synthesis: Option<SynthesisInfo>,
    /// Texels the store gained.
    pub texels_added: u64,
    /// Store bytes before the insert.
    pub bytes_before: u64,
    /// Store bytes after it.
    pub bytes_after: u64,
    /// Wall time: voxelization, synthesis and insert.
    pub time: Duration,
}

/// The colour of a procedural (or volume) texture at voxel `v` of a grid of resolution `r`,
/// as sRGB-encoded RGBA8.
fn procedural_colour(material: &crate::scene::Material, r: u32) -> impl Fn([u32; 3]) -> u32 + Sync {
    let gm = GpuMaterial::from(material);
    let volume = material.texture.as_ref().and_then(|t| t.volume.clone());
    move |v: [u32; 3]| match &volume {
        // Already sRGB bytes.
        Some(volume) => {
            let [r_, g, b] = volume.at_voxel(v, r).map(|c| c as u32);
            r_ | g << 8 | b << 16 | 255 << 24
        }
        None => {
            let centre = (Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32) + 0.5) / r as f32;
            pack_srgb8(solid_texture_albedo(&gm, centre))
        }
    }
}

/// What the stores of one scene share while they are built: kernels, the voxelizer, and one
/// lazy synthesis state per synthesized texture (exemplar, seed, resolution), so meshes that
/// share a texture share its voxels and nothing is synthesized twice.
struct Baker<'a> {
    gpu: &'a Gpu,
    kernels: Option<Arc<StoreKernels>>,
    voxelizer: Option<Voxelizer>,
    lazy: HashMap<(PathBuf, u32, u32), GpuLazySolid>,
}

/// The lazy synthesis state of exemplar `spec` at resolution `r`, with the solid defaults and
/// the candidates through the user's cache.
fn lazy_state(gpu: &Gpu, spec: &SynthesizedSpec, r: u32) -> Result<GpuLazySolid, SynthError> {
    let image = load_solid(&spec.exemplar, FitMode::Auto, None)?.exemplar;
    let exemplars = SolidExemplars::new(image, [None, None, None])?;
    let cache = DiskCache::user().ok();
    GpuLazySolid::with_defaults(gpu, &exemplars, spec.seed, r, cache.as_ref())
}

impl Baker<'_> {
    fn kernels(&mut self) -> Result<Arc<StoreKernels>, RenderError> {
        Ok(match &self.kernels {
            Some(k) => k.clone(),
            None => self.kernels.insert(StoreKernels::new(self.gpu)?).clone(),
        })
    }

    /// The voxels a store of `spec` holds for the triangles (surface voxels for nearest reads
    /// and for a TileTree, interpolation voxels for trilinear reads), or `None` for a TileTree
    /// of a procedural texture, which needs no voxels.
    fn voxels(
        &mut self,
        spec: StoreSpec,
        synthesized: bool,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
    ) -> Result<Option<VoxelKeys>, String> {
        if spec.kind == StoreKind::TileTree && !synthesized {
            return Ok(None);
        }
        let gpu = self.gpu;
        let voxelizer = match &mut self.voxelizer {
            Some(v) => v,
            None => self
                .voxelizer
                .insert(Voxelizer::new(gpu).map_err(|e| e.to_string())?),
        };
        let r = spec.resolution;
        let keys = match (spec.kind, spec.filter) {
            (StoreKind::TileTree, _) | (_, StoreFilter::Nearest) => {
                voxelizer.surface(positions, triangles, r)
            }
            (_, StoreFilter::Trilinear) => voxelizer.interpolation(positions, triangles, r),
        };
        keys.map(Some).map_err(|e| e.to_string())
    }

    /// The synthesized colours of `keys` (lazily: only voxels no earlier request computed),
    /// with what the synthesis did.
    fn synthesize(
        &mut self,
        synth: &SynthesizedSpec,
        r: u32,
        keys: &VoxelKeys,
    ) -> Result<(GpuBuffer<u32>, SynthesisInfo), String> {
        let key = (synth.exemplar.clone(), synth.seed, r);
        if !self.lazy.contains_key(&key) {
            let state = lazy_state(self.gpu, synth, r).map_err(|e| e.to_string())?;
            self.lazy.insert(key.clone(), state);
        }
        let lazy = self.lazy.get_mut(&key).expect("inserted above");
        let start = Instant::now();
        let (colours, report) = lazy.colours(keys).map_err(|e| e.to_string())?;
        let stats = SynthesisInfo {
            versions: report.computed.iter().sum(),
            finest: report.needed.last().copied().unwrap_or(0),
            state_bytes: lazy.bytes(),
            time: start.elapsed(),
        };
        Ok((colours, stats))
    }

    /// Bakes the texture of `material` on `mesh` into the store `spec` asks for, and inserts
    /// the cap faces of the pieces cut from it (`caps`: positions and triangles in the mesh's
    /// coordinates), which a second request synthesizes.
    fn bake(
        &mut self,
        scene: &Scene,
        mesh: usize,
        material: usize,
        caps: Option<(&[Vec3], &[[u32; 3]])>,
    ) -> Result<(SceneStore, Option<SynthesisInfo>, Option<CutInfo>), RenderError> {
        let material = &scene.materials[material];
        let mesh = &scene.meshes[mesh];
        let spec = material
            .texture
            .as_ref()
            .and_then(|t| t.store)
            .expect("only textures with a store are baked");
        let kernels = self.kernels()?;
        let r = spec.resolution;
        let colour = procedural_colour(material, r);
        let (positions, triangles) = (&mesh.mesh.positions, &mesh.mesh.triangles);
        let context = |what: &str, e: &dyn std::fmt::Display| {
            RenderError::Settings(format!(
                "{}: baking material {:?} on mesh {:?}{what}: {e}",
                scene.source.display(),
                material.name,
                mesh.name
            ))
        };
        let synth = material
            .texture
            .as_ref()
            .and_then(|t| t.synthesized.clone());
        let keys = self
            .voxels(spec, synth.is_some(), positions, triangles)
            .map_err(|e| context("", &e))?;
        let (colours, stats) = match (&synth, &keys) {
            (Some(synth), Some(keys)) => {
                let (c, s) = self
                    .synthesize(synth, r, keys)
                    .map_err(|e| context("", &e))?;
                (Some(c), Some(s))
            }
            _ => (None, None),
        };
        let source = match (&keys, &colours) {
            (Some(keys), Some(colours)) => ColourSource::Buffer { keys, colours },
            _ => ColourSource::Fn(&colour),
        };
        let mut store = self.fill(&kernels, spec, positions, triangles, keys.as_ref(), &source)?;
        let cut = match caps {
            Some((cap_positions, cap_triangles)) if !cap_triangles.is_empty() => Some(
                self.insert_caps(
                    &mut store,
                    spec,
                    synth.as_ref(),
                    &colour,
                    keys.as_ref(),
                    (cap_positions, cap_triangles),
                )
                .map_err(|e| context(" (cut faces)", &e))?,
            ),
            _ => None,
        };
        Ok((store, stats, cut))
    }

    /// Inserts the cap faces into a store built over the outer surface: a volume store gets the
    /// caps' voxels it does not hold yet, a TileTree the cap triangles; for a synthesized
    /// texture only those voxels are requested from the lazy state, which computes what no
    /// earlier request did.
    #[allow(clippy::too_many_arguments)]
    fn insert_caps(
        &mut self,
        store: &mut SceneStore,
        spec: StoreSpec,
        synth: Option<&SynthesizedSpec>,
        colour: &(dyn Fn([u32; 3]) -> u32 + Sync),
        outer_keys: Option<&VoxelKeys>,
        caps: (&[Vec3], &[[u32; 3]]),
    ) -> Result<CutInfo, String> {
        let start = Instant::now();
        let gpu = self.gpu;
        let r = spec.resolution;
        let cap_keys = self.voxels(spec, synth.is_some(), caps.0, caps.1)?;
        // What the store gets: a volume store only voxels it lacks; a TileTree's buffer source
        // must hold every voxel its refilled texels meet, which the outer and cap voxels do.
        let requested = cap_keys.as_ref().map_or(0, |k| k.len() as u64);
        let new_keys = match (cap_keys, outer_keys) {
            (Some(cap), Some(outer)) => {
                let (cap, outer) = (
                    cap.read().map_err(|e| e.to_string())?,
                    outer.read().map_err(|e| e.to_string())?,
                );
                let wanted: Vec<u64> = if spec.kind == StoreKind::TileTree {
                    let mut all: Vec<u64> = cap.iter().chain(&outer).copied().collect();
                    all.sort_unstable();
                    all.dedup();
                    all
                } else {
                    cap.into_iter()
                        .filter(|k| outer.binary_search(k).is_err())
                        .collect()
                };
                Some(
                    VoxelKeys::from_sorted(gpu, "cut voxels", &wanted)
                        .map_err(|e| e.to_string())?,
                )
            }
            // Nothing was stored by voxel: the caps' voxels are all new.
            (cap, None) => cap,
            (None, Some(_)) => None,
        };
        let (colours, synthesis) = match (synth, &new_keys) {
            (Some(synth), Some(keys)) if !keys.is_empty() => {
                let (c, s) = self.synthesize(synth, r, keys)?;
                (Some(c), Some(s))
            }
            _ => (None, None),
        };
        let source = match (&new_keys, &colours) {
            (Some(keys), Some(colours)) => ColourSource::Buffer { keys, colours },
            _ => ColourSource::Fn(colour),
        };
        let (texels_before, bytes_before) = store.size();
        match &mut *store {
            SceneStore::TileTree(t) => {
                t.insert_surface(caps.0, caps.1, &source)
                    .map_err(|e| e.to_string())?;
            }
            other => {
                let keys = new_keys.as_ref().expect("volume stores have voxels");
                if !keys.is_empty() {
                    match other {
                        SceneStore::Hash(s) => s.insert(keys, &source),
                        SceneStore::Octree(s) => s.insert(keys, &source),
                        SceneStore::Perfect(s) => s.insert(keys, &source),
                        SceneStore::TileTree(_) => unreachable!("handled above"),
                    }
                    .map_err(|e| e.to_string())?;
                }
            }
        }
        let (texels_after, bytes_after) = store.size();
        Ok(CutInfo {
            cap_triangles: caps.1.len() as u64,
            requested_voxels: requested,
            new_voxels: new_keys.as_ref().map_or(0, |k| k.len() as u64),
            synthesis,
            texels_added: texels_after.saturating_sub(texels_before),
            bytes_before,
            bytes_after,
            time: start.elapsed(),
        })
    }

    /// Builds the store `spec` asks for over `keys` (the TileTree: over the mesh, without
    /// keys) with the colours of `source`.
    fn fill(
        &self,
        kernels: &Arc<StoreKernels>,
        spec: StoreSpec,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        keys: Option<&VoxelKeys>,
        source: &ColourSource<'_>,
    ) -> Result<SceneStore, RenderError> {
        let r = spec.resolution;
        let keys = || keys.expect("every store but the TileTree is given its voxels");
        Ok(match spec.kind {
            StoreKind::CoherentHash => SceneStore::Hash(
                HashStore::build(kernels, r, keys(), source, RobinHoodConfig::default())
                    .map_err(store_error)?,
            ),
            StoreKind::Octree => {
                let config = OctreeConfig::for_resolution(r).map_err(store_error)?;
                let (s, _) =
                    OctreeStore::build(kernels, r, keys(), source, config).map_err(store_error)?;
                SceneStore::Octree(s)
            }
            StoreKind::PerfectHash => SceneStore::Perfect(
                PerfectStore::build(kernels, r, keys(), source, PerfectAccess::Constrained)
                    .map_err(store_error)?,
            ),
            StoreKind::TileTree => {
                let (s, _) = TileTree::build(
                    kernels,
                    positions,
                    triangles,
                    r,
                    source,
                    TileTreeConfig::default(),
                )
                .map_err(store_error)?;
                SceneStore::TileTree(s)
            }
        })
    }
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
        let mut baker = Baker {
            gpu,
            kernels: None,
            voxelizer: None,
            lazy: HashMap::new(),
        };
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
            let (store, synthesis, cut) = baker.bake(
                scene,
                root,
                inst.material,
                caps.as_ref().map(|(p, t)| (&p[..], &t[..])),
            )?;
            let (texels, bytes) = store.size();
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
            stores.push((store, spec.filter));
            slot_of.insert((root, inst.material), slot);
            slots[i] = slot;
        }
        let records = Self::upload(gpu, &stores)?;
        Ok(SceneStores {
            gpu: gpu.clone(),
            stores,
            records,
            instance_slots: GpuBuffer::from_slice(gpu, "render instance stores", &slots)?,
            info,
        })
    }

    /// The store of `slot` (in the order of [`SceneStores::info`]), to insert texels into;
    /// call [`SceneStores::refresh`] before the next render.
    pub fn store_mut(&mut self, slot: usize) -> Option<&mut SceneStore> {
        self.stores.get_mut(slot).map(|(s, _)| s)
    }

    /// The records of `stores` on the device (one default record when there is no store:
    /// bindings cannot be empty).
    fn upload(
        gpu: &Gpu,
        stores: &[(SceneStore, StoreFilter)],
    ) -> Result<DeviceRecords, RenderError> {
        let mut records: Vec<GpuStoreRecord<'_>> =
            stores.iter().map(|(s, f)| s.record(*f)).collect();
        if records.is_empty() {
            records.push(GpuStoreRecord::default());
        }
        Ok(DeviceRecords::new(gpu, "render store records", &records)?)
    }

    /// The record of every store as the kernel reads it after the next
    /// [`SceneStores::refresh`] (or now, when no store changed since the last).
    pub fn records(&self) -> Vec<GpuStoreRecord<'_>> {
        self.stores.iter().map(|(s, f)| s.record(*f)).collect()
    }

    /// One bit per `STORE_KIND_*` the scene's stores use: the path tracer compiles only those
    /// lookups.
    pub fn kinds_mask(&self) -> u32 {
        self.records().iter().fold(0, |mask, r| mask | 1 << r.kind)
    }

    /// Rewrites the kernel's records from the stores' current buffers (after inserts, which
    /// may have reallocated them) and their sizes in [`SceneStores::info`].
    ///
    /// # Errors
    /// Device failures.
    pub fn refresh(&mut self) -> Result<(), RenderError> {
        self.records = Self::upload(&self.gpu, &self.stores)?;
        for ((store, _), info) in self.stores.iter().zip(&mut self.info) {
            (info.texels, info.bytes) = store.size();
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

    /// What was baked.
    pub fn info(&self) -> &[BakedStoreInfo] {
        &self.info
    }
}

/// The cap faces of every piece cut from mesh `root` that an instance shows with `material`, as
/// one triangle list (each piece's vertices appended), or `None` when nothing was cut from it.
fn caps_of(scene: &Scene, root: usize, material: usize) -> Option<(Vec<Vec3>, Vec<[u32; 3]>)> {
    let mut pieces: Vec<usize> = scene
        .instances
        .iter()
        .filter(|i| i.material == material)
        .map(|i| i.mesh)
        .filter(|&m| matches!(&scene.meshes[m].cut_from, Some((r, _)) if *r == root))
        .collect();
    pieces.sort_unstable();
    pieces.dedup();
    if pieces.is_empty() {
        return None;
    }
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for m in pieces {
        let (mesh, flags) = (&scene.meshes[m].mesh, &scene.meshes[m].cut_from.as_ref()?.1);
        let base = positions.len() as u32;
        positions.extend_from_slice(&mesh.positions);
        triangles.extend(
            mesh.triangles
                .iter()
                .zip(flags)
                .filter(|(_, &cap)| cap)
                .map(|(t, _)| t.map(|v| v + base)),
        );
    }
    Some((positions, triangles))
}

fn store_error(e: impl std::fmt::Display) -> RenderError {
    RenderError::Settings(format!("sparse store: {e}"))
}
