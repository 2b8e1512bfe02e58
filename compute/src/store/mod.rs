//! Sparse textures of RGBA8 colours over the voxels of a surface at resolution R: the storage
//! of lazysolid's synthesized matter. Every store implements [`SparseStore`]: built from a
//! voxel key set ([`VoxelKeys`], Morton keys as the voxelizer returns them) and a
//! [`ColourSource`], extended by further voxels as cuts appear, measured in exact GPU bytes,
//! and read from any kernel through a small record of device addresses (the store's
//! `Params`, which borrows the store) and a GLSL include `glsl/include/store/<name>.glsl` with
//! `vec4 store_<name>_nearest(Params, vec3 pos)` and `vec4 store_<name>_trilinear(...)`,
//! `pos` in [0, 1]³ object space. A voxel that is not stored reads as (0, 0, 0, 0).
//! Layouts, byte counts and timings: `docs/stores.md`.
//!
//! - [`HashStore`]: the coherent Robin Hood hash keyed by Morton keys, payload = colour index;
//! - [`OctreeStore`]: an N³-tree texture (Lefebvre, Hornus and Neyret 2005) in a node pool,
//!   N chosen per level, with per-node average colours for MIP filtering;
//! - [`TileTree`]: 2D tiles on the faces of the leaves of an octree around the surface
//!   (Lefebvre and Dachsbacher 2007), built from the mesh itself; its lookup needs the surface
//!   normal ([`SparseStore::lookup_with_normals`]).

pub(crate) mod colours;
mod error;
pub(crate) mod hash_store;
mod kernels;
mod keys;
mod lookup_cpu;
mod marble;
pub(crate) mod octree;
mod octree_cpu;
pub(crate) mod perfect_store;
pub mod tiletree;

pub use colours::{colours_by_key_cpu, ColourSource, HostColours};
pub use error::StoreError;
pub use hash_store::{HashStore, HashStoreParams};
pub use kernels::{LookupMode, StoreKernels, TimedLookup};
pub use keys::key_outside_grid;
pub use lookup_cpu::{
    nearest_cpu, nearest_voxel, trilinear_cpu, trilinear_footprint, trilinear_sample_cpu,
    unpack_rgba8, StoreSample,
};
pub use marble::{
    marble_band, marble_band_at, marble_rgba8, MARBLE_BAND_ONE, MARBLE_BASE_FREQUENCY,
};
pub use octree::{OctreeConfig, OctreeParams, OctreeStore, MAX_OCTREE_LEVELS};
pub use octree_cpu::OctreeCpu;
pub use perfect_store::{PerfectStore, PerfectStoreParams};
pub use tiletree::{TileTree, TileTreeConfig, TileTreeParams, TileTreeStats};

use crate::gpu::PushValue;
use crate::voxel::VoxelKeys;
use glam::{Vec3, Vec4};

/// How a lookup filters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// The texel of the voxel containing the point.
    Nearest,
    /// The 8 texels around the point, weighted (the stored set must hold the interpolation
    /// voxels of the surface, see [`crate::voxel::Voxelizer::interpolation`]).
    Trilinear,
}

/// What a build or insert did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StoreReport {
    /// Texels stored in all.
    pub texels: u64,
    /// Texels added by this call.
    pub added: u64,
    /// Every reallocation of a GPU buffer, with its reason and sizes.
    pub reallocations: Vec<String>,
}

/// What a store's inserts add. Volume stores are sets of voxels (or of interpolation cells)
/// and grow by keys; a surface store's texels follow a mesh, so it grows by triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InsertUnit {
    /// Voxel keys of the R³ grid ([`SparseStore::insert`]).
    Voxels,
    /// Interpolation cells (keys of the grid shifted by half a voxel, as
    /// [`crate::voxel::VoxelGrid::cells`]), for the blocked perfect hash
    /// ([`SparseStore::insert`]).
    Cells,
    /// Surface triangles in unit-cube coordinates ([`SparseStore::insert_surface`]): the
    /// TileTree.
    Surface,
}

/// A sparse RGBA8 texture over the voxels of an R³ grid.
pub trait SparseStore {
    /// The record a kernel receives (device addresses and sizes), laid out as the GLSL struct
    /// of the store's include file. It borrows the store, whose buffers its addresses point
    /// into, so an insert (which may reallocate them) cannot happen while one is alive.
    type Params<'a>: PushValue
    where
        Self: 'a;

    /// Short name: the include is `store/<name>.glsl`, the GLSL functions `store_<name>_*`.
    fn name(&self) -> &'static str;

    /// R.
    fn resolution(&self) -> u32;

    /// Texels stored.
    fn len(&self) -> u64;

    /// True when no texel is stored.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// What [`SparseStore::insert`] or [`SparseStore::insert_surface`] takes.
    fn insert_unit(&self) -> InsertUnit;

    /// Adds the voxels (or cells, see [`SparseStore::insert_unit`]) `keys`, none of which may
    /// be stored yet, with their colours: lazy synthesis adds texels as cuts appear. A store
    /// that outgrows its buffers reallocates or rebuilds (reported). Surface stores refuse
    /// ([`StoreError::Unsupported`]): use [`SparseStore::insert_surface`].
    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError>;

    /// Adds surface triangles (unit-cube coordinates, outward-facing, indices into
    /// `positions`), e.g. the caps of a cut, with the colours of their voxels. Volume stores
    /// refuse ([`StoreError::Unsupported`]): insert the triangles' surface or interpolation
    /// voxels with [`SparseStore::insert`].
    fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        let _ = (positions, triangles, colours);
        Err(StoreError::Unsupported {
            store: self.name(),
            what: "insert of surface triangles (a volume store grows by voxel keys: insert the triangles' voxels)",
        })
    }

    /// Exact GPU bytes the store keeps allocated.
    fn bytes(&self) -> u64;

    /// The kernel-side description, borrowing the store (see [`SparseStore::Params`]).
    fn params(&self) -> Self::Params<'_>;

    /// Runs the store's GLSL lookup at `points` on the GPU (tests and benchmarks).
    fn lookup(&self, points: &[Vec3], filter: Filter) -> Result<Vec<Vec4>, StoreError> {
        self.lookup_with_normals(points, &[], filter)
    }

    /// Runs the store's GLSL lookup at surface points with their normals: what a renderer has
    /// at a hit, and what a surface store (the TileTree picks a tile face from the normal)
    /// needs. Volume stores ignore the normals.
    fn lookup_with_normals(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        filter: Filter,
    ) -> Result<Vec<Vec4>, StoreError> {
        let lookup = self.timed_lookup(points, normals, filter)?;
        lookup.run()?;
        Ok(lookup.results()?)
    }

    /// Runs the store's GLSL sample lookup (what a relief reads: the filtered sum, its
    /// coverage and the gradient of alpha) at `points` with their `normals` (volume stores
    /// ignore them).
    fn sample_lookup(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
    ) -> Result<Vec<StoreSample>, StoreError> {
        let lookup = self.timed_lookup_mode(points, normals, LookupMode::Sample)?;
        lookup.run()?;
        Ok(lookup.samples()?)
    }

    /// Uploads `points` (and `normals`, which volume stores ignore) once and returns a lookup
    /// that can be run and timed repeatedly: how benchmarks compare the structures' lookup cost
    /// without the transfers.
    fn timed_lookup(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        filter: Filter,
    ) -> Result<TimedLookup<'_>, StoreError> {
        self.timed_lookup_mode(points, normals, filter.into())
    }

    /// [`SparseStore::timed_lookup`] of any [`LookupMode`].
    fn timed_lookup_mode(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        mode: LookupMode,
    ) -> Result<TimedLookup<'_>, StoreError>;
}
