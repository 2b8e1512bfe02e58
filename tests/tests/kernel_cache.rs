//! The device's kernel cache seen from the builders: a second build of a store, or a store of
//! another kind, builds no pipeline twice, and a builder builds only the pipelines it uses.

use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, HashStore, OctreeConfig, OctreeStore, SparseStore, StoreKernels,
};
use lazysolid_compute::voxel::Voxelizer;
use lazysolid_tests::{unit_mesh, with_fresh_gpu};

#[test]
fn building_stores_again_creates_no_pipelines() {
    with_fresh_gpu(|gpu| {
        let mesh = unit_mesh("cube.off");
        let r = 32;
        let keys = Voxelizer::new(gpu)
            .unwrap()
            .surface(&mesh.positions, &mesh.triangles, r)
            .unwrap();
        let source = ColourSource::Marble { seed: 1 };
        let octree = |kernels: &std::sync::Arc<StoreKernels>| {
            let config = OctreeConfig::for_resolution(r).unwrap();
            let (store, _) = OctreeStore::build(kernels, r, &keys, &source, config).unwrap();
            store.len()
        };

        let kernels = StoreKernels::new(gpu).unwrap();
        let voxelizer_only = gpu.pipelines_created();
        assert_eq!(octree(&kernels), keys.len as u64);
        let first = gpu.pipelines_created();
        assert!(first > voxelizer_only, "the octree needs pipelines");
        // An octree build needs no hash kernel but the key check every store applies: the
        // context builds kernels when they are used.
        let names = gpu.cached_kernels();
        assert!(
            names
                .iter()
                .all(|n| !n.starts_with("hash/") || *n == "hash/check_keys.comp"),
            "an octree build built hash kernels: {names:?}"
        );
        assert!(names.contains(&"hash/check_keys.comp"), "{names:?}");
        assert!(names.contains(&"store/octree_link.comp"), "{names:?}");

        // The same store again, from the same context and from a fresh one: no new pipeline.
        octree(&kernels);
        octree(&StoreKernels::new(gpu).unwrap());
        assert_eq!(gpu.pipelines_created(), first);

        // A hash store builds only what it adds (the Robin Hood kernels, the fill); a second
        // one builds nothing.
        let hash = || {
            HashStore::build(&kernels, r, &keys, &source, RobinHoodConfig::default())
                .unwrap()
                .len()
        };
        hash();
        let with_hash = gpu.pipelines_created();
        assert!(with_hash > first);
        hash();
        octree(&kernels);
        assert_eq!(gpu.pipelines_created(), with_hash);
    });
}
