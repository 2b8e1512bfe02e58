//! The render `lazysolid solid` makes of its volume: a cube and a sphere carved out of it,
//! through the path tracer and the N³ octree store, from a scene file written beside the
//! volume (so the user can render it again with `lazysolid render`).

use anyhow::Context;
use lazysolid_compute::gpu::Gpu;
use lazysolid_renderer::output::Film;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use std::path::Path;

/// Samples per pixel of the render.
pub const RENDER_SPP: u32 = 32;

/// The scene of a cube and a sphere carved out of the `n`³ volume in `volume_file` (a path
/// relative to the scene's folder): each mesh spans the volume's unit cube, so the cube shows
/// the volume's outer faces and the sphere cuts into it; the octree store holds the voxels at
/// the volume's own resolution, read nearest, so every texel is one synthesized voxel.
pub fn carved_scene(volume_file: &str, n: u32) -> String {
    // A TOML basic string: backslashes and quotes escaped.
    let volume_file = volume_file.replace('\\', "\\\\").replace('"', "\\\"");
    format!(
        r#"# A cube and a sphere carved out of {volume_file}, written by `lazysolid solid`.
# Render it again with: lazysolid render THIS.toml -o OUT.png

[camera]
position = [0.9, 2.3, 3.9]
look_at = [0.9, 0.45, 0.5]
fov_y = 36

[render]
width = 400
height = 240
spp = {RENDER_SPP}
max_depth = 4

[[mesh]]
name = "cube"
shape = "cube"

[[mesh]]
name = "sphere"
shape = "sphere"
subdivisions = 4

[[mesh]]
name = "ground"
shape = "quad"

[[material]]
name = "matter"
kind = "lambertian"
texture = {{ kind = "volume", path = "{volume_file}", store = "octree", resolution = {n} }}

[[material]]
name = "floor"
kind = "lambertian"
color = [0.35, 0.35, 0.35]

[[instance]]
mesh = "cube"
material = "matter"
rotate = [0, 25, 0]
translate = [-0.2, 0, 0.2]

[[instance]]
mesh = "sphere"
material = "matter"
translate = [1.2, 0, 0]

[[instance]]
mesh = "ground"
material = "floor"
scale = 20
translate = [-10, 0, -10]

[[light]]
kind = "sphere"
center = [-2.5, 5, 4]
radius = 0.8
radiance = [40, 38, 34]

[environment]
radiance = [0.25, 0.27, 0.3]
"#
    )
}

/// Renders the carved scene of `nrrd` (the volume's file bytes, side `n`) in a temporary
/// folder, so that nothing is written beside the output before everything is computed.
///
/// # Errors
/// A scene or render failure.
pub fn render_carved(gpu: &Gpu, nrrd: &[u8], n: u32) -> anyhow::Result<Film> {
    let dir = tempfile::Builder::new()
        .prefix("lazysolid-solid-render-")
        .tempdir()
        .context("creating a temporary folder for the render")?;
    let volume = dir.path().join("volume.nrrd");
    std::fs::write(&volume, nrrd).with_context(|| format!("writing {}", volume.display()))?;
    let scene_path = dir.path().join("carved.toml");
    let scene = Scene::parse(&carved_scene("volume.nrrd", n), &scene_path)?;
    let mut tracer = PathTracer::new(gpu, &scene).context("preparing the carved render")?;
    Ok(tracer.render(|_| {})?)
}

/// The file name of `path`, for a scene beside it.
pub fn file_name(path: &Path) -> String {
    path.file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned()
}
