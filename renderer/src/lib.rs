//! lazysolid's renderer crate: scenes, meshes and (as it lands) the path tracer.
//!
//! It holds mesh loading, which every structure builder and benchmark needs (OBJ through tobj
//! and OFF, the format of the CGAL meshes `scripts/fetch-assets.sh` installs), the resolved scene
//! types, and the shading data of the path tracer with a CPU reference of its GLSL library.

pub mod accel;
pub mod mesh;
pub mod scene;
pub mod shading;
