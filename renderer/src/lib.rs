//! lazysolid's renderer crate: scenes, meshes and (as it lands) the path tracer.
//!
//! For now it holds mesh loading, which every structure builder and benchmark needs: OBJ through
//! tobj and OFF (the format of the CGAL meshes `scripts/fetch-assets.sh` installs).

pub mod accel;
pub mod mesh;
pub mod scene;
