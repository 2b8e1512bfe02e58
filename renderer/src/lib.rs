//! lazysolid's renderer crate: scenes, meshes and (as it lands) the path tracer.
//!
//! It holds mesh loading, which every structure builder and benchmark needs (OBJ through tobj and
//! OFF, the format of the CGAL meshes `scripts/fetch-assets.sh` installs), and the TOML scene
//! loader that turns a scene file into what the path tracer renders (`docs/scenes.md`).

pub mod mesh;
pub mod scene;
