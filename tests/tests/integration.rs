//! The workspace's integration tests, one module per structure or system (the file of the
//! same name beside this one), built as one test binary: the shared code is compiled and
//! linked once instead of once per file, and one run schedules every test across the cores,
//! so no file's slowest test leaves a core idle before the next file starts
//! (`docs/testing.md`). `cargo test -p lazysolid-tests --test integration render::` runs one
//! module. The fuzz tests stay a binary of their own (`fuzz/`): their counting allocator
//! measures the whole process.

mod core;
mod docs;
mod fit;
mod fracture;
mod glint;
mod glint_bsdf;
mod glint_material;
mod glint_range_query;
mod hash;
mod kernel_cache;
mod lazy;
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
