//! The TOML scene loader: the example scenes, every class of error (with file, line and field),
//! instance transforms, the built-in shapes, textures and their stores, fractures and
//! explosions.
//!
//! One test binary (`cargo test -p lazysolid-renderer --test scene`), so the tests cost one
//! link: a module per part of the scene format, and the fixtures and helpers they share in
//! `support`.

mod errors;
mod explosion;
mod fields;
mod files;
mod fracture;
mod shapes;
mod shipped;
mod stores;
mod support;
mod synthesized;
