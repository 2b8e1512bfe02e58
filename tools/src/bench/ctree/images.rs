//! The test content of `bench ctree`, all made or fetched by lazysolid itself: smooth fields
//! (a terrain height field, a lat-long sky environment map, a slice of a mesh's distance field)
//! and a photograph as the hard case, plus the mesh's distance volume for the 3D trees.

use anyhow::Context;
use lazysolid_compute::ctree::fields::terrain;
use lazysolid_compute::gpu::Gpu;
use lazysolid_compute::hash::morton_decode;
use lazysolid_compute::voxel::Voxelizer;
use lazysolid_renderer::mesh::Mesh;
use lazysolid_synth::Exemplar;
use std::path::Path;

/// One test image: grey (one channel) or RGB.
pub struct TestImage {
    /// Short name for tables and files.
    pub name: String,
    /// What it is, for the report.
    pub what: String,
    /// Width and height.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// 1 (grey) or 3 (RGB).
    pub channels: u32,
    /// Texels, rows first, `channels` bytes each.
    pub texels: Vec<u8>,
}

impl TestImage {
    fn grey(name: &str, what: &str, width: u32, height: u32, values: &[f32]) -> TestImage {
        TestImage {
            name: name.into(),
            what: what.into(),
            width,
            height,
            channels: 1,
            texels: values
                .iter()
                .map(|v| v.round().clamp(0.0, 255.0) as u8)
                .collect(),
        }
    }
}

/// The fractal terrain height field.
pub fn terrain_image(side: u32) -> TestImage {
    let field = terrain(side, side, 7);
    TestImage::grey(
        "terrain",
        "fractal terrain height field (5 octaves of value noise)",
        side,
        side,
        &field.values,
    )
}

/// A lat-long sky: the horizon-to-zenith gradient of a clear sky, a sun with its glow, and a
/// darker ground below the horizon, in sRGB.
pub fn sky_image(side: u32) -> TestImage {
    let (w, h) = (side, side / 2);
    let sun = glam::Vec3::new(0.4, 0.35, -0.85).normalize();
    let mut texels = Vec::with_capacity((3 * w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let theta = std::f32::consts::PI * (y as f32 + 0.5) / h as f32;
            let phi = 2.0 * std::f32::consts::PI * (x as f32 + 0.5) / w as f32;
            let d = glam::Vec3::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                -theta.sin() * phi.cos(),
            );
            let up = d.y;
            let c = if up >= 0.0 {
                let zenith = glam::Vec3::new(0.16, 0.32, 0.75);
                let horizon = glam::Vec3::new(0.75, 0.82, 0.92);
                let t = up.powf(0.45);
                let sky = horizon.lerp(zenith, t);
                let cos = d.dot(sun).max(0.0);
                sky + glam::Vec3::new(1.0, 0.85, 0.6)
                    * (0.6 * cos.powf(24.0) + 3.0 * cos.powf(900.0))
            } else {
                let ground = glam::Vec3::new(0.3, 0.27, 0.22);
                ground.lerp(glam::Vec3::new(0.6, 0.62, 0.64), (1.0 + up).powf(8.0))
            };
            for v in c.to_array() {
                texels.push((255.0 * v.clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8);
            }
        }
    }
    TestImage {
        name: "sky".into(),
        what: "lat-long sky environment map (gradient, sun and glow, ground)".into(),
        width: w,
        height: h,
        channels: 3,
        texels,
    }
}

/// The photograph: an exemplar of the assets.
pub fn photo_image(path: &Path) -> anyhow::Result<TestImage> {
    let e = Exemplar::load(path).with_context(|| format!("loading {}", path.display()))?;
    Ok(TestImage {
        name: "photo".into(),
        what: format!(
            "photograph {} ({}×{})",
            path.file_stem().unwrap_or_default().to_string_lossy(),
            e.width,
            e.height
        ),
        width: e.width,
        height: e.height,
        channels: 3,
        texels: e.rgb.iter().flatten().copied().collect(),
    })
}

/// The unsigned distance from every voxel centre of an `r`³ grid to the mesh's surface voxels,
/// in voxels: the surface voxelized on the device, then an exact Euclidean distance transform
/// (the lower envelope of parabolas along each axis in turn).
pub fn distance_volume(gpu: &Gpu, mesh: &Mesh, r: u32) -> anyhow::Result<Vec<f32>> {
    let mut voxelizer = Voxelizer::new(gpu)?;
    let keys = voxelizer
        .surface(&mesh.positions, &mesh.triangles, r)?
        .read()?;
    let n = r as usize;
    let mut d2 = vec![f32::INFINITY; n * n * n];
    for k in keys {
        let [x, y, z] = morton_decode(k, 3);
        d2[x as usize + n * (y as usize + n * z as usize)] = 0.0;
    }
    for axis in 0..3 {
        let stride = [1, n, n * n][axis];
        let mut line = vec![0f32; n];
        let mut out = vec![0f32; n];
        for a in 0..n {
            for b in 0..n {
                let base = match axis {
                    0 => n * (a + n * b),
                    1 => a + n * n * b,
                    _ => a + n * b,
                };
                for (i, v) in line.iter_mut().enumerate() {
                    *v = d2[base + i * stride];
                }
                lower_envelope(&line, &mut out);
                for (i, &v) in out.iter().enumerate() {
                    d2[base + i * stride] = v;
                }
            }
        }
    }
    Ok(d2.into_iter().map(f32::sqrt).collect())
}

/// min over j of f(j) + (i − j)², for every i (Felzenszwalb and Huttenlocher 2012).
fn lower_envelope(f: &[f32], out: &mut [f32]) {
    let n = f.len();
    let mut v = vec![0usize; n];
    let mut z = vec![0f32; n + 1];
    let mut k = 0usize;
    let first = f.iter().position(|x| x.is_finite());
    let Some(first) = first else {
        out.fill(f32::INFINITY);
        return;
    };
    v[0] = first;
    z[0] = f32::NEG_INFINITY;
    z[1] = f32::INFINITY;
    for q in first + 1..n {
        if !f[q].is_finite() {
            continue;
        }
        loop {
            let p = v[k];
            let s = ((f[q] + (q * q) as f32) - (f[p] + (p * p) as f32)) / (2.0 * (q - p) as f32);
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                // k == 0 and the new parabola wins everywhere.
                v[0] = q;
                z[1] = f32::INFINITY;
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f32::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f32 {
            k += 1;
        }
        let p = v[k];
        *o = (q as f32 - p as f32).powi(2) + f[p];
    }
}

/// Distances (voxels) to grey levels: 0 on the surface, 255 at `range` voxels and beyond.
pub fn distance_grey(d: f32, range: f32) -> f32 {
    (255.0 * d / range).clamp(0.0, 255.0)
}

/// The middle z slice of a distance volume as a test image.
pub fn distance_slice(volume: &[f32], r: u32, mesh_name: &str) -> TestImage {
    let n = r as usize;
    let z = n / 2;
    let values: Vec<f32> = (0..n * n)
        .map(|i| distance_grey(volume[i + n * n * z], r as f32 / 4.0))
        .collect();
    TestImage::grey(
        "distance",
        &format!("distance field of the {mesh_name} mesh, middle slice"),
        r,
        r,
        &values,
    )
}

#[cfg(test)]
mod tests {
    use super::lower_envelope;

    #[test]
    fn the_lower_envelope_is_the_brute_force_minimum() {
        let f = [
            f32::INFINITY,
            3.0,
            f32::INFINITY,
            0.0,
            7.0,
            f32::INFINITY,
            1.0,
            9.0,
        ];
        let mut out = [0f32; 8];
        lower_envelope(&f, &mut out);
        for (i, &o) in out.iter().enumerate() {
            let brute = f
                .iter()
                .enumerate()
                .map(|(j, &v)| v + ((i as f32) - (j as f32)).powi(2))
                .fold(f32::INFINITY, f32::min);
            assert_eq!(o, brute, "{i}");
        }
    }
}
