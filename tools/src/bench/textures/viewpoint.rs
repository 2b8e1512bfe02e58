//! The fixed viewpoint of the texture benchmark: the surface points (and normals) an 800×800
//! pinhole camera sees of a mesh in the unit cube, in the 8×8-tile order a renderer launches
//! its pixels, each with the pixel it belongs to so that lookups can be drawn as a picture.

use glam::Vec3;
use lazysolid_renderer::accel::{GpuRay, InstanceDesc, SceneBvh, NO_HIT};
use lazysolid_renderer::mesh::Mesh;
use rayon::prelude::*;

/// What the camera sees.
pub struct Viewpoint {
    /// Pixels per side.
    pub size: u32,
    /// Surface point of each covered pixel, in the mesh's unit-cube space.
    pub points: Vec<Vec3>,
    /// Unit geometric normal (the mesh's winding) at each point.
    pub normals: Vec<Vec3>,
    /// Row-major pixel index of each point.
    pub pixels: Vec<u32>,
}

/// The camera of thesis Fig. 4.8 is a frontal view filling the window; this one looks at the
/// centre of the mesh's bounds along +z (the armadillo faces −z) from a distance where a 30°
/// field of view frames them.
pub fn view(mesh: &Mesh, size: u32) -> Viewpoint {
    let (lo, hi) = mesh.positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let centre = (lo + hi) * 0.5;
    let half_extent = ((hi - lo) * 0.5).truncate().max_element() * 1.05;
    let half = (30f32.to_radians() * 0.5).tan();
    let eye = centre - Vec3::new(0.0, 0.0, half_extent / half + (hi.z - lo.z) * 0.5);
    let scene = SceneBvh::build(
        &[mesh],
        &[InstanceDesc {
            mesh: 0,
            material: 0,
            transform: glam::Affine3A::IDENTITY,
        }],
    );
    let tiles = size.div_ceil(8);
    let pixels: Vec<u32> = (0..tiles * tiles * 64)
        .filter_map(|i| {
            let (tile, within) = (i / 64, i % 64);
            let x = (tile % tiles) * 8 + within % 8;
            let y = (tile / tiles) * 8 + within / 8;
            (x < size && y < size).then_some(y * size + x)
        })
        .collect();
    let hits: Vec<Option<(u32, Vec3, Vec3)>> = pixels
        .par_iter()
        .map(|&pixel| {
            let (x, y) = (pixel % size, pixel / size);
            let sx = ((x as f32 + 0.5) / size as f32 * 2.0 - 1.0) * half;
            let sy = (1.0 - (y as f32 + 0.5) / size as f32 * 2.0) * half;
            let ray = GpuRay {
                origin: eye.into(),
                tmin: 0.0,
                // Looking along +z with +y up, +x is to the left: −sx keeps the picture unmirrored.
                direction: Vec3::new(-sx, sy, 1.0).normalize().into(),
                tmax: f32::INFINITY,
            };
            let hit = scene.trace_cpu(&ray);
            (hit.instance != NO_HIT).then(|| {
                let [a, b, c] =
                    mesh.triangles[hit.triangle as usize].map(|i| mesh.positions[i as usize]);
                let p = a * (1.0 - hit.u - hit.v) + b * hit.u + c * hit.v;
                let n = (b - a).cross(c - a).normalize_or_zero();
                (pixel, p.clamp(Vec3::ZERO, Vec3::ONE), n)
            })
        })
        .collect();
    let mut view = Viewpoint {
        size,
        points: Vec::new(),
        normals: Vec::new(),
        pixels: Vec::new(),
    };
    for (pixel, p, n) in hits.into_iter().flatten() {
        view.pixels.push(pixel);
        view.points.push(p);
        view.normals.push(n);
    }
    view
}

/// The looked-up colours drawn at their pixels over a dark background (RGB8).
pub fn picture(view: &Viewpoint, colours: &[glam::Vec4]) -> Vec<u8> {
    let mut rgb = vec![24u8; (view.size * view.size * 3) as usize];
    for (&pixel, c) in view.pixels.iter().zip(colours) {
        let at = pixel as usize * 3;
        for (k, v) in [c.x, c.y, c.z].into_iter().enumerate() {
            rgb[at + k] = (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
        }
    }
    rgb
}
