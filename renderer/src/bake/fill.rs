//! One store of the kind a scene names, built over keys (or, for the TileTree, over the mesh)
//! with the colours of a source: the only place the renderer chooses a store's configuration.

use crate::render::SceneStore;
use crate::scene::{StoreKind, StoreSpec};
use glam::Vec3;
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, HashStore, OctreeConfig, OctreeStore, PerfectStore, StoreError, StoreKernels,
    TileTree, TileTreeConfig,
};
use lazysolid_compute::voxel::VoxelKeys;
use std::sync::Arc;

/// Builds the store `spec` asks for over `keys` (the TileTree: over the mesh, without keys)
/// with the colours of `source`.
pub(super) fn fill(
    kernels: &Arc<StoreKernels>,
    spec: StoreSpec,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    keys: Option<&VoxelKeys>,
    source: &ColourSource<'_>,
) -> Result<SceneStore, StoreError> {
    let r = spec.resolution;
    let keys = || keys.expect("every store but the TileTree is given its voxels");
    Ok(match spec.kind {
        StoreKind::CoherentHash => SceneStore::Hash(HashStore::build(
            kernels,
            r,
            keys(),
            source,
            RobinHoodConfig::default(),
        )?),
        StoreKind::Octree => {
            let config = OctreeConfig::for_resolution(r)?;
            let (s, _) = OctreeStore::build(kernels, r, keys(), source, config)?;
            SceneStore::Octree(s)
        }
        StoreKind::PerfectHash => SceneStore::Perfect(PerfectStore::build(
            kernels,
            r,
            keys(),
            source,
            PerfectAccess::Constrained,
        )?),
        StoreKind::TileTree => {
            let (s, _) = TileTree::build(
                kernels,
                positions,
                triangles,
                r,
                source,
                TileTreeConfig::default(),
            )?;
            SceneStore::TileTree(s)
        }
    })
}
