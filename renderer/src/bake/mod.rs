//! The bake: a scene's solid textures put into sparse stores. For every (mesh, material) pair
//! whose texture asks for a store, the mesh's surface voxels (or interpolation voxels, for
//! trilinear reads) get the texture's colours — synthesized lazily for a synthesized texture,
//! per voxel for a procedural or volume one — through one owner of matter in a store
//! ([`StoredMatter`]), which then grows by the cap faces of the pieces cut from the mesh.
//! `render/stores.rs` turns the results into the records the path tracer reads.

mod caps;
mod colour;
mod fill;

pub(crate) use caps::caps_of;

use crate::render::{RenderError, SceneStore};
use crate::scene::{Material, Scene, StoreFilter, StoreKind, SynthesizedSpec};
use colour::procedural_colour;
use fill::fill;
use glam::Vec3;
use lazysolid_compute::gpu::Gpu;
use lazysolid_compute::store::StoreKernels;
use lazysolid_compute::voxel::Voxelizer;
use lazysolid_synth::cache::DiskCache;
use lazysolid_synth::relief::relief_pixels_per_alpha;
use lazysolid_synth::solid::lazy::{
    CutInfo, GpuLazySolid, MatterColours, MatterSpec, MatterVoxels, MemoryPolicy, SharedLazy,
    StoredMatter, SynthesisInfo,
};
use lazysolid_synth::SynthError;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// A scene's store with what it was made from.
pub(crate) type Matter = StoredMatter<SceneStore>;

/// What the stores of one scene share while they are built: kernels, the voxelizer, and one
/// lazy synthesis state per synthesized texture (exemplar, seed, resolution), so meshes that
/// share a texture share its voxels and nothing is synthesized twice.
pub(crate) struct Baker<'a> {
    gpu: &'a Gpu,
    kernels: Option<Arc<StoreKernels>>,
    voxelizer: Option<Voxelizer>,
    lazy: HashMap<(PathBuf, u32, u32, MemoryPolicy, bool), SharedLazy>,
}

/// The lazy synthesis state of `spec`'s recipe at resolution `r`, with the candidates
/// through the user's cache.
fn lazy_state(gpu: &Gpu, spec: &SynthesizedSpec, r: u32) -> Result<GpuLazySolid, SynthError> {
    let cache = DiskCache::user().ok();
    spec.recipe()
        .load()?
        .prepare(gpu, cache.as_ref(), &mut |_, _| {})?
        .lazy(gpu, r, spec.policy)
}

impl<'a> Baker<'a> {
    /// A baker for `gpu`; kernels and the voxelizer are made at their first use.
    pub(crate) fn new(gpu: &'a Gpu) -> Baker<'a> {
        Baker {
            gpu,
            kernels: None,
            voxelizer: None,
            lazy: HashMap::new(),
        }
    }

    fn kernels(&mut self) -> Result<Arc<StoreKernels>, RenderError> {
        Ok(match &self.kernels {
            Some(k) => k.clone(),
            None => self.kernels.insert(StoreKernels::new(self.gpu)?).clone(),
        })
    }

    fn voxelizer(&mut self) -> Result<&mut Voxelizer, RenderError> {
        if self.voxelizer.is_none() {
            self.voxelizer = Some(
                Voxelizer::new(self.gpu)
                    .map_err(|e| RenderError::Settings(format!("voxelizer: {e}")))?,
            );
        }
        Ok(self.voxelizer.as_mut().expect("made above"))
    }

    /// Where the colours of `material`'s texture come from at resolution `r`: the texture's
    /// shared lazy state (made at its first use), or its procedural colour per voxel.
    fn colours(&mut self, material: &Material, r: u32) -> Result<MatterColours, SynthError> {
        let synth = material
            .texture
            .as_ref()
            .and_then(|t| t.synthesized.as_ref());
        let Some(synth) = synth else {
            return Ok(MatterColours::Voxel(Arc::new(procedural_colour(
                material, r,
            ))));
        };
        let recipe = synth.recipe();
        let key = (recipe.exemplar, recipe.seed, r, synth.policy, recipe.relief);
        if let Some(lazy) = self.lazy.get(&key) {
            return Ok(MatterColours::Lazy(lazy.clone()));
        }
        let lazy = Arc::new(Mutex::new(lazy_state(self.gpu, synth, r)?));
        self.lazy.insert(key, lazy.clone());
        Ok(MatterColours::Lazy(lazy))
    }

    /// Bakes the texture of `material` on `mesh` into the store `spec` asks for, and grows it
    /// by the cap faces of the pieces cut from it (`caps`: positions and triangles in the
    /// mesh's coordinates), which a second request synthesizes. Also returns the relief's
    /// object-space height per unit of the stored alpha (0 without relief): `relief` (the
    /// walls' slope) times the relief code's pixels of feature distance per unit of alpha,
    /// over R (one exemplar pixel is one voxel at the finest level).
    pub(crate) fn bake(
        &mut self,
        scene: &Scene,
        mesh: usize,
        material: usize,
        caps: Option<(&[Vec3], &[[u32; 3]])>,
    ) -> Result<(Matter, Option<SynthesisInfo>, Option<CutInfo>, f32), RenderError> {
        let material = &scene.materials[material];
        let mesh = &scene.meshes[mesh];
        let spec = material
            .texture
            .as_ref()
            .and_then(|t| t.store)
            .expect("only textures with a store are baked");
        let kernels = self.kernels()?;
        let r = spec.resolution;
        let (positions, triangles) = (&mesh.mesh.positions, &mesh.mesh.triangles);
        let context = |what: &str, e: &dyn std::fmt::Display| {
            RenderError::Settings(format!(
                "{}: baking material {:?} on mesh {:?}{what}: {e}",
                scene.source.display(),
                material.name,
                mesh.name
            ))
        };
        let colours = self.colours(material, r).map_err(|e| context("", &e))?;
        let relief = match (
            &colours,
            material
                .texture
                .as_ref()
                .and_then(|t| t.synthesized.as_ref()),
        ) {
            (MatterColours::Lazy(lazy), Some(synth)) if synth.relief > 0.0 => {
                let lazy = lazy.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
                let clamp = lazy.relief().map_or(0.0, |rel| rel.clamp());
                synth.relief * relief_pixels_per_alpha(clamp) / r as f32
            }
            _ => 0.0,
        };
        let voxels = match (spec.kind, spec.filter, &colours) {
            (StoreKind::TileTree, _, MatterColours::Voxel(_)) => MatterVoxels::Unkeyed,
            (StoreKind::TileTree, _, _) | (_, StoreFilter::Nearest, _) => MatterVoxels::Surface,
            (_, StoreFilter::Trilinear, _) => MatterVoxels::Interpolation,
        };
        let gpu = self.gpu;
        let voxelizer = self.voxelizer()?;
        let (mut matter, stats) = StoredMatter::build(
            gpu,
            voxelizer,
            MatterSpec {
                colours,
                voxels,
                resolution: r,
            },
            positions,
            triangles,
            |keys, source| fill(&kernels, spec, positions, triangles, keys, source),
        )
        .map_err(|e| context("", &e))?;
        let cut = match caps {
            Some((cap_positions, cap_triangles)) if !cap_triangles.is_empty() => Some(
                matter
                    .grow(voxelizer, cap_positions, cap_triangles)
                    .map_err(|e| context(" (cut faces)", &e))?,
            ),
            _ => None,
        };
        Ok((matter, stats, cut, relief))
    }
}
