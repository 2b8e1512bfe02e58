//! The render `lazysolid solid` makes of its volume: a cube and a sphere carved out of it,
//! through the path tracer and the N³ octree store. The scene is built in memory from the
//! volume's colours ([`carved`]); the same scene as a file ([`carved_scene`]) is written beside
//! the volume, so the user can render it again with `lazysolid render`, and a test keeps the
//! two equal.

use anyhow::Context;
use glam::{Affine3A, Quat, Vec3};
use lazysolid_compute::gpu::Gpu;
use lazysolid_renderer::mesh::Mesh;
use lazysolid_renderer::output::Film;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{
    Camera, Environment, Instance, Lens, Light, Material, MaterialKind, RenderSettings, Scene,
    SceneMesh, SolidTexture, StoreFilter, StoreKind, StoreSpec, VolumeTexture, DEFAULT_RR_DEPTH,
};
use std::path::{Path, PathBuf};

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

/// The carved scene of an `n`³ volume (`colours`, x fastest), in memory: what
/// [`carved_scene`] describes, with `source` as the scene file it would come from and the
/// volume read from `volume_path` beside it.
pub fn carved(colours: &[[u8; 3]], n: u32, source: PathBuf, volume_path: PathBuf) -> Scene {
    let volume = VolumeTexture {
        path: volume_path,
        size: [n; 3],
        rgb: colours.to_vec(),
    };
    let matter = SolidTexture::of_volume(
        volume,
        Some(StoreSpec {
            kind: StoreKind::Octree,
            resolution: n,
            filter: StoreFilter::Nearest,
        }),
    );
    let lambertian = |name: &str, color: Vec3, texture: Option<SolidTexture>| Material {
        name: name.into(),
        kind: MaterialKind::Lambertian,
        color,
        k: Vec3::ZERO,
        emission: Vec3::ZERO,
        roughness: 0.0,
        ior: 1.0,
        texture,
        glint: None,
        albedo_map: None,
        normal_map: None,
    };
    let mesh = |name: &str, mesh: Mesh| SceneMesh {
        name: name.into(),
        mesh,
        cut_from: None,
    };
    let place = |mesh, material, scale: f32, rotate_y_deg: f32, translate: Vec3| Instance {
        mesh,
        material,
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::splat(scale),
            Quat::from_rotation_y(rotate_y_deg * (std::f32::consts::PI / 180.0)),
            translate,
        ),
        piece: None,
    };
    Scene {
        source,
        camera: Camera {
            position: Vec3::new(0.9, 2.3, 3.9),
            look_at: Vec3::new(0.9, 0.45, 0.5),
            up: Vec3::Y,
            fov_y_deg: 36.0,
            lens: Lens::Pinhole,
        },
        render: RenderSettings {
            width: 400,
            height: 240,
            spp: RENDER_SPP,
            max_depth: 4,
            rr_depth: DEFAULT_RR_DEPTH,
            seed: 0,
        },
        meshes: vec![
            mesh("cube", Mesh::unit_cube()),
            mesh("sphere", Mesh::icosphere(4)),
            mesh("ground", Mesh::unit_quad()),
        ],
        materials: vec![
            lambertian(
                "matter",
                (matter.color_a + matter.color_b) * 0.5,
                Some(matter),
            ),
            lambertian("floor", Vec3::splat(0.35), None),
        ],
        instances: vec![
            place(0, 0, 1.0, 25.0, Vec3::new(-0.2, 0.0, 0.2)),
            place(1, 0, 1.0, 0.0, Vec3::new(1.2, 0.0, 0.0)),
            place(2, 1, 20.0, 0.0, Vec3::new(-10.0, 0.0, -10.0)),
        ],
        lights: vec![Light::Sphere {
            center: Vec3::new(-2.5, 5.0, 4.0),
            radius: 0.8,
            radiance: Vec3::new(40.0, 38.0, 34.0),
        }],
        environment: Environment::Constant(Vec3::new(0.25, 0.27, 0.3)),
        explosion: None,
        animation: None,
    }
}

/// Renders [`carved`] of the volume `colours` (side `n`) written as `volume_path`, with the
/// scene file it would come from `source`: nothing is written before everything is computed.
///
/// # Errors
/// A render failure.
pub fn render_carved(
    gpu: &Gpu,
    colours: &[[u8; 3]],
    n: u32,
    source: PathBuf,
    volume_path: PathBuf,
) -> anyhow::Result<Film> {
    let scene = carved(colours, n, source, volume_path);
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

#[cfg(test)]
mod tests {
    use super::*;
    use lazysolid_synth::solid::encode_nrrd;

    /// The scene built in memory is the scene file written beside the volume, read back:
    /// camera, settings, materials (the volume included), placements, lights and meshes.
    #[test]
    fn the_carved_scene_is_its_file() {
        let dir = tempfile::tempdir().unwrap();
        let n = 8;
        let colours: Vec<[u8; 3]> = (0..n * n * n)
            .map(|i| [(i * 7 % 256) as u8, (i * 13 % 256) as u8, (i % 256) as u8])
            .collect();
        let volume = dir.path().join("v.nrrd");
        std::fs::write(&volume, encode_nrrd(&colours, n, &[])).unwrap();
        let source = dir.path().join("v.scene.toml");
        std::fs::write(&source, carved_scene("v.nrrd", n)).unwrap();
        let read = Scene::load(&source).unwrap();
        let built = carved(&colours, n, source.clone(), volume);
        assert_eq!(built.source, read.source);
        assert_eq!(built.camera, read.camera);
        assert_eq!(built.render, read.render);
        assert_eq!(built.materials, read.materials);
        assert_eq!(built.instances, read.instances);
        assert_eq!(built.lights, read.lights);
        assert_eq!(built.environment, read.environment);
        assert!(built.explosion.is_none() && read.explosion.is_none());
        assert!(built.animation.is_none() && read.animation.is_none());
        assert_eq!(built.meshes.len(), read.meshes.len());
        for (b, r) in built.meshes.iter().zip(&read.meshes) {
            assert_eq!(b.name, r.name);
            assert_eq!(b.mesh.positions, r.mesh.positions, "{}", b.name);
            assert_eq!(b.mesh.triangles, r.mesh.triangles, "{}", b.name);
            assert!(b.cut_from.is_none() && r.cut_from.is_none());
        }
    }
}
