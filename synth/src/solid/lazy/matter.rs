//! Matter in a store: the one owner of a solid texture baked into a sparse store. It holds
//! where the colours come from (a lazy synthesis state, or a function of the voxel), the store,
//! and the voxels the store's texels were made from. It is built over a surface, and it grows
//! by a new surface (the caps of a cut) through the store's own insert unit, asking the lazy
//! state only for voxels the store does not hold, so no voxel is synthesized twice. The
//! renderer's bake and `bench cuts` both go through it, so the two cannot drift apart.

use super::gpu::{GpuLazySolid, LazyReport};
use crate::SynthError;
use glam::Vec3;
use lazysolid_compute::gpu::{Gpu, GpuBuffer, GpuError};
use lazysolid_compute::store::{ColourSource, InsertUnit, SparseStore, StoreError, StoreReport};
use lazysolid_compute::voxel::{KeySets, VoxelError, VoxelGrid, VoxelKeys, Voxelizer};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Where matter is kept: any [`SparseStore`], or a caller's enum over several kinds (the
/// renderer's scene stores) that forwards to one.
pub trait MatterStore {
    /// What the store's inserts take (see [`SparseStore::insert_unit`]).
    fn insert_unit(&self) -> InsertUnit;
    /// [`SparseStore::insert`].
    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError>;
    /// [`SparseStore::insert_surface`].
    fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError>;
    /// Texels stored and exact GPU bytes.
    fn size(&self) -> (u64, u64);
}

impl<S: SparseStore> MatterStore for S {
    fn insert_unit(&self) -> InsertUnit {
        SparseStore::insert_unit(self)
    }

    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        SparseStore::insert(self, keys, colours)
    }

    fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        SparseStore::insert_surface(self, positions, triangles, colours)
    }

    fn size(&self) -> (u64, u64) {
        (self.len(), self.bytes())
    }
}

/// A lazy synthesis state shared by every store of one texture (meshes that share a texture
/// share its voxels).
pub type SharedLazy = Arc<Mutex<GpuLazySolid>>;

/// Where a store's colours come from.
#[derive(Clone)]
pub enum MatterColours {
    /// Synthesized lazily: only the voxels a store needs, and only once.
    Lazy(SharedLazy),
    /// A function of the voxel (sRGB-encoded RGBA8), e.g. a procedural or volume texture.
    Voxel(Arc<dyn Fn([u32; 3]) -> u32 + Send + Sync>),
}

/// The voxels a store's texels are made from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatterVoxels {
    /// Voxels a surface passes through: what nearest reads and the TileTree's texels meet.
    Surface,
    /// Voxels of the interpolation cells a surface passes through: what trilinear reads meet.
    Interpolation,
    /// None: a store built from the surface alone with colours of [`MatterColours::Voxel`]
    /// (the TileTree of a procedural texture).
    Unkeyed,
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
    /// Device time of the synthesis kernels, milliseconds.
    pub gpu_ms: f64,
    /// Wall time of the request.
    pub time: Duration,
}

/// What growing by a new surface (the cap faces of cut or fractured pieces) did.
#[derive(Clone, Copy, Debug)]
pub struct CutInfo {
    /// Triangles of the new surface.
    pub cap_triangles: u64,
    /// Voxels the new surface needs (surface or interpolation voxels).
    pub requested_voxels: u64,
    /// Of those, voxels the store did not hold (for a surface store: the voxels its colour
    /// buffer covers, held and new).
    pub new_voxels: u64,
    /// The lazy synthesis of those voxels, for synthesized matter.
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

/// Why matter could not be built or grown.
#[derive(Debug, thiserror::Error)]
pub enum MatterError {
    /// Voxelizing the surface failed.
    #[error("voxelizing: {0}")]
    Voxels(#[from] VoxelError),
    /// The lazy synthesis failed.
    #[error(transparent)]
    Synthesis(#[from] SynthError),
    /// The store refused the build or the insert.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A device failure outside those.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The store grows by interpolation cells (the blocked perfect hash), which matter built
    /// from voxels cannot give it.
    #[error("the store grows by interpolation cells; matter in it grows by voxels or surfaces")]
    Cells,
    /// Lazy matter without voxels: nothing would say which voxels to synthesize.
    #[error("synthesized matter needs voxels (surface or interpolation), not an unkeyed store")]
    UnkeyedLazy,
}

/// What matter is made of and at which grid.
#[derive(Clone)]
pub struct MatterSpec {
    /// Where its colours come from.
    pub colours: MatterColours,
    /// The voxels its store's texels are made from.
    pub voxels: MatterVoxels,
    /// Voxels per unit of the grid.
    pub resolution: u32,
}

/// A solid texture in a store, and what it was made from.
pub struct StoredMatter<S> {
    colours: MatterColours,
    store: S,
    voxels: MatterVoxels,
    resolution: u32,
    /// The voxels the store's texels were made from, sorted, on the device (`None` when
    /// unkeyed).
    held: Option<VoxelKeys>,
    /// Union and difference of key sets on the device.
    sets: KeySets,
}

impl<S: MatterStore> StoredMatter<S> {
    /// Builds the matter `spec` over the surface `positions`/`triangles` (unit-cube
    /// coordinates): voxelizes it as the spec says, takes the voxels' colours from the spec's
    /// source (synthesizing them, for lazy matter) and lets `build` make the store from
    /// the keys (`None` when unkeyed) and the colours.
    ///
    /// # Errors
    /// Voxelization, synthesis and store failures; [`MatterError::Cells`] for a store that
    /// grows by cells, [`MatterError::UnkeyedLazy`] for lazy matter without voxels.
    pub fn build(
        gpu: &Gpu,
        voxelizer: &mut Voxelizer,
        spec: MatterSpec,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        build: impl FnOnce(Option<&VoxelKeys>, &ColourSource<'_>) -> Result<S, StoreError>,
    ) -> Result<(StoredMatter<S>, Option<SynthesisInfo>), MatterError> {
        let MatterSpec {
            colours,
            voxels,
            resolution,
        } = spec;
        if matches!(colours, MatterColours::Lazy(_)) && voxels == MatterVoxels::Unkeyed {
            return Err(MatterError::UnkeyedLazy);
        }
        let keys = voxelize(voxelizer, voxels, positions, triangles, resolution)?;
        let synthesized = match (&colours, &keys) {
            (MatterColours::Lazy(lazy), Some(keys)) => Some(synthesize(lazy, keys)?),
            _ => None,
        };
        let store = {
            let source = source(&colours, keys.as_ref(), synthesized.as_ref());
            build(keys.as_ref(), &source)?
        };
        if store.insert_unit() == InsertUnit::Cells {
            return Err(MatterError::Cells);
        }
        Ok((
            StoredMatter {
                colours,
                store,
                voxels,
                resolution,
                held: keys,
                sets: KeySets::new(gpu)?,
            },
            synthesized.map(|(_, info)| info),
        ))
    }

    /// Grows the matter by the surface `positions`/`triangles` (the caps of a cut): a voxel
    /// store gets the new surface's voxels it does not hold, a surface store the triangles
    /// with colours over every voxel its new texels meet. Lazy matter synthesizes only the
    /// voxels no earlier request computed.
    ///
    /// # Errors
    /// As [`StoredMatter::build`].
    pub fn grow(
        &mut self,
        voxelizer: &mut Voxelizer,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
    ) -> Result<CutInfo, MatterError> {
        let start = Instant::now();
        let unit = self.store.insert_unit();
        let cap = voxelize(
            voxelizer,
            self.voxels,
            positions,
            triangles,
            self.resolution,
        )?;
        let requested = cap.as_ref().map_or(0, |k| k.len() as u64);
        let bits = VoxelGrid::voxels(self.resolution)?.key_bits();
        // A voxel store gets only the voxels it lacks; a surface store's colour buffer must
        // hold every voxel its refilled texels meet, which the held and new voxels do. The
        // keys stay on the device.
        let keys = match (&cap, &self.held, unit) {
            (_, _, InsertUnit::Cells) => return Err(MatterError::Cells),
            (Some(cap), Some(held), InsertUnit::Surface) => Some(self.sets.union(held, cap, bits)?),
            (Some(cap), Some(held), _) => Some(self.sets.difference(cap, held, bits)?),
            _ => None,
        };
        let synthesized = match (&self.colours, &keys) {
            (MatterColours::Lazy(lazy), Some(keys)) if !keys.is_empty() => {
                Some(synthesize(lazy, keys)?)
            }
            _ => None,
        };
        let (texels_before, bytes_before) = self.store.size();
        {
            let source = source(&self.colours, keys.as_ref(), synthesized.as_ref());
            match unit {
                InsertUnit::Surface => {
                    self.store.insert_surface(positions, triangles, &source)?;
                }
                _ => {
                    if let Some(keys) = keys.as_ref().filter(|k| !k.is_empty()) {
                        self.store.insert(keys, &source)?;
                    }
                }
            }
        }
        let new_voxels = keys.as_ref().map_or(0, |k| k.len() as u64);
        // The held voxels grow by the new surface's: a surface store's keys already are the
        // union.
        let grown = match (unit, keys, &cap, &self.held) {
            (InsertUnit::Surface, Some(union), _, _) => Some(union),
            (_, _, Some(cap), Some(held)) => Some(self.sets.union(held, cap, bits)?),
            _ => None,
        };
        if grown.is_some() {
            self.held = grown;
        }
        let (texels_after, bytes_after) = self.store.size();
        Ok(CutInfo {
            cap_triangles: triangles.len() as u64,
            requested_voxels: requested,
            new_voxels,
            synthesis: synthesized.map(|(_, info)| info),
            texels_added: texels_after.saturating_sub(texels_before),
            bytes_before,
            bytes_after,
            time: start.elapsed(),
        })
    }

    /// The store, to read or render from.
    pub fn store(&self) -> &S {
        &self.store
    }

    /// The store, e.g. for a caller's own inserts (which this owner then does not know of).
    pub fn store_mut(&mut self) -> &mut S {
        &mut self.store
    }

    /// The voxels the store's texels were made from: sorted Morton keys on the device, `None`
    /// for a store made from a surface alone.
    pub fn held(&self) -> Option<&VoxelKeys> {
        self.held.as_ref()
    }

    /// Bytes of the kept lazy synthesis state (0 for matter of a voxel function).
    pub fn state_bytes(&self) -> u64 {
        match &self.colours {
            MatterColours::Lazy(lazy) => lazy.lock().map_or(0, |l| l.bytes()),
            MatterColours::Voxel(_) => 0,
        }
    }
}

/// The keys of the voxels `voxels` asks for, `None` when unkeyed.
fn voxelize(
    voxelizer: &mut Voxelizer,
    voxels: MatterVoxels,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    resolution: u32,
) -> Result<Option<VoxelKeys>, VoxelError> {
    Ok(match voxels {
        MatterVoxels::Surface => Some(voxelizer.surface(positions, triangles, resolution)?),
        MatterVoxels::Interpolation => {
            Some(voxelizer.interpolation(positions, triangles, resolution)?)
        }
        MatterVoxels::Unkeyed => None,
    })
}

/// The colours of `keys` from the lazy state, on the device in key order.
fn synthesize(
    lazy: &SharedLazy,
    keys: &VoxelKeys,
) -> Result<(GpuBuffer<u32>, SynthesisInfo), SynthError> {
    let mut lazy = lazy.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let start = Instant::now();
    let (colours, report): (GpuBuffer<u32>, LazyReport) = lazy.colours(keys)?;
    let info = SynthesisInfo {
        versions: report.computed.iter().sum(),
        finest: report.needed.last().copied().unwrap_or(0),
        state_bytes: lazy.bytes(),
        gpu_ms: report.gpu_ms,
        time: start.elapsed(),
    };
    Ok((colours, info))
}

/// The colour source of a build or an insert: the synthesized buffer over `keys`, or the
/// voxel function.
fn source<'a>(
    colours: &'a MatterColours,
    keys: Option<&'a VoxelKeys>,
    synthesized: Option<&'a (GpuBuffer<u32>, SynthesisInfo)>,
) -> ColourSource<'a> {
    match (colours, keys, synthesized) {
        (_, Some(keys), Some((buffer, _))) => ColourSource::Buffer {
            keys,
            colours: buffer,
        },
        (MatterColours::Voxel(f), _, _) => ColourSource::Fn(f.as_ref()),
        // Lazy matter is always keyed (`build` refuses it unkeyed): this is an empty request,
        // which inserts nothing by key.
        (MatterColours::Lazy(_), _, _) => ColourSource::Fn(&no_colour),
    }
}

fn no_colour(_: [u32; 3]) -> u32 {
    0
}
