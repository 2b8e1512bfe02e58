//! Scenes: the resolved scene types and the TOML scene loader ([`Scene::load`],
//! [`Scene::parse`]). `docs/scenes.md` has the same reference with a complete example.
//!
//! # Format
//! Colours are `[r, g, b]` in linear RGB, points and directions `[x, y, z]` in world units,
//! angles in degrees. Relative paths start at the scene file's folder. Unknown keys are
//! errors, and so are keys that the table's `kind` (or form) does not use.
//!
//! - `[camera]` (required): `position`, `look_at`, `up` (default `[0, 1, 0]`, not parallel
//!   to the view direction), `fov_y` (vertical, in (0, 180)); optionally `aperture_radius`
//!   and `focus_distance` together (both > 0) for a thin lens, otherwise a pinhole.
//! - `[render]` (required): `width`, `height` (1..=8192), `spp` (1..=1 048 576), `max_depth`
//!   (0..=64 bounces, default 8; 0 shows only emitters), `rr_depth` (0..=64, default 3; Russian roulette never starts when it
//!   is ≥ `max_depth`), `seed` (default 0).
//! - `[[mesh]]`: a unique `name` and either `path` (an `.obj` or `.off` file, scaled into the
//!   unit cube [0, 1]^3 by [`Mesh::normalize_to_unit_cube`](crate::mesh::Mesh) unless
//!   `normalize = false`) or `shape`: `"quad"` (the square [0, 1] × {0} × [0, 1] facing +y),
//!   `"cube"` ([0, 1]^3) or `"sphere"` (centre 0.5, radius 0.5, with `subdivisions` 0..=7 of
//!   the icosahedron, default 3). Shapes are already in the unit cube and take no `normalize`.
//! - `[[material]]`: a unique `name` and a `kind`:
//!   - `"lambertian"`: `color` (albedo, each channel in [0, 1]) or `texture`;
//!   - `"plastic"`: `color` or `texture`, `roughness` ([0, 1]), `ior` of the coat ((1, 4],
//!     default 1.5);
//!   - `"conductor"`: `roughness`, and `preset = "gold" | "silver" | "copper" | "aluminium"`
//!     or both `color` (η) and `k` (κ), each channel ≥ 0;
//!   - `"dielectric"`: `ior` ((1, 4]), `roughness` (default 0: smooth), `color` (transmission
//!     tint in [0, 1], default white);
//!   - `"emissive"`: `emission` (radiance, ≥ 0).
//!
//!   `texture = { kind = "marble" | "wood" | "checker", color_a, color_b, scale }` (scale > 0,
//!   default 1: features per unit of object space) replaces `color` as the albedo; so does
//!   `texture = { kind = "volume", path }`, an RGB NRRD volume stretched over the unit cube,
//!   which needs `store` and `resolution` (it is read through the store only); and so does
//!   `texture = { kind = "synthesized", exemplar, seed }`, matter synthesized lazily from an
//!   exemplar (asset name or path) over the unit cube.
//! - `[[instance]]` (at least one): `mesh` and `material` by name, `scale` (> 0, default 1),
//!   `rotate` (default `[0, 0, 0]`: degrees about the world x, then y, then z axis),
//!   `translate` (default `[0, 0, 0]`); the object-to-world transform is
//!   translate · rotate · scale. The scale is a single number because solid textures are
//!   evaluated in the mesh's rest-pose object space: a non-uniform scale would stretch them.
//!   An instance may have a `name` (unique) for the tables below to refer to.
//! - `[[cut]]`: `instance` (a name), `point` and `normal` (non-zero) of a plane in the mesh's
//!   coordinates (its unit cube); cuts apply in file order, each to every piece so far, and a
//!   plane that misses the mesh is an error.
//! - `[[fracture]]` (one per instance): `instance`, and `pieces` (1..=1024) with `seed`
//!   (default 1) for sites drawn inside the mesh, or `sites = [[x, y, z], ...]` in the mesh's
//!   coordinates; applied after the cuts, to every piece. The mesh must be closed. The
//!   instance is replaced by one instance per piece, each piece a closed mesh in the broken
//!   mesh's coordinates with its cap faces marked (`SceneMesh::cut_from`); its texture is read
//!   at rest-pose coordinates, so the matter stays continuous across the cracks.
//! - `[explosion]` (needs a cut or fracture): `speed` (world units/s, in [0, 10000]), `spin`
//!   (degrees/s, default 0; each piece turns at 50–100 % of it about its own axis), `gravity`
//!   (default `[0, -9.81, 0]`), `start` (seconds, default 0), `centre` (world; default the
//!   centre of each broken instance's bounds).
//! - `[animation]`: `frames` (1..=100000) and `fps` ((0, 1000]); frame k shows time k / fps.
//! - `[[light]]`: `kind = "sphere"` with `center`, `radius` (> 0), `radiance`; or
//!   `kind = "quad"` with `corner`, `edge_u`, `edge_v` (not parallel), `radiance` and
//!   `two_sided` (default false: emits towards `edge_u × edge_v`).
//! - `[environment]` (default black): `radiance = [r, g, b]`, or `path` to an EXR lat-long
//!   map (must exist) with `intensity` (> 0, default 1) and `rotation` (degrees about +y,
//!   default 0).
//!
//! Every error names the scene file, the line and the field path, e.g.
//! `scenes/a.toml:14: material "glass".ior: 0.8 is out of range (must be in (1, 4])`.

mod broken;
mod camera;
mod check;
mod error;
mod lights;
mod location;
mod material;
mod meshes;
mod motion;
mod raw;
mod resolve;
mod types;
mod volume;

pub use camera::{DEFAULT_MAX_DEPTH, DEFAULT_RR_DEPTH, MAX_DEPTH, MAX_IMAGE_SIDE, MAX_SPP};
pub use error::SceneError;
pub use meshes::DEFAULT_SPHERE_SUBDIVISIONS;
pub use types::*;
pub use volume::{VolumeTexture, MAX_VOLUME_TEXTURE_SIDE};
