//! The workspace's integration tests, one module per structure or system (the file of the
//! same name beside this one), built as one test binary: the shared code is compiled and
//! linked once instead of once per file, and one run schedules every test across the cores,
//! so no file's slowest test leaves a core idle before the next file starts
//! (`docs/testing.md`). `cargo test -p lazysolid-tests --test integration render::` runs one
//! module. The fuzz tests stay a binary of their own (`fuzz/`): their counting allocator
//! measures the whole process.

mod core;
mod ctree;
mod docs;
mod export;
mod fit;
mod fracture;
mod glint;
mod glint_bsdf;
mod glint_material;
mod glint_range_query;
mod hash;
mod kernel_cache;
mod lazy;
mod manifold;
mod mesh;
mod multiscale;
mod normal_maps;
mod perfect_hash;
mod prims;
mod push_blocks;
mod quality;
mod recipe;
mod relief;
mod render;
mod shading;
mod solid;
mod store;
mod store_samples;
mod synth;
mod synth_cache;
mod tiletree;
mod trace;
mod transport;
mod uv_maps;
mod voxel;

/// With `autotests = false` (tests/Cargo.toml), cargo builds only the test binaries it is told
/// of, so a new file beside this one that is not a module here would never be built or run:
/// every `.rs` file here is a module of this binary, and every folder is a `[[test]]` of its
/// own.
#[test]
fn every_test_file_is_built() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let this = include_str!("integration.rs");
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let mut checked = 0;
    for entry in std::fs::read_dir(root.join("tests")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            let target = format!("path = \"tests/{name}/main.rs\"");
            assert!(manifest.contains(&target), "tests/{name}/ is no [[test]]");
        } else if let Some(module) = name.strip_suffix(".rs") {
            if module != "integration" {
                let declared = format!("\nmod {module};\n");
                assert!(this.contains(&declared), "tests/{name} is no module");
            }
        }
        checked += 1;
    }
    assert!(checked > 30, "{checked} entries");
}
