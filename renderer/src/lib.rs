//! lazysolid's renderer crate: scenes, meshes and (as it lands) the path tracer.
//!
//! It holds mesh loading, which every structure builder and benchmark needs (OBJ through tobj
//! and OFF, the format of the CGAL meshes `scripts/fetch-assets.sh` installs), the image output
//! of a render (EXR and tone-mapped PNG) and FLIP image comparison.

pub mod diff;
pub mod mesh;
pub mod output;
pub mod scene;
