//! One piece's texture atlas: its surface unwrapped into charts (uvunwrap: segmentation, LSCM
//! and packing, in Rust, with no C++ toolchain to build), then every texel whose centre lies
//! on a chart given the matter at the object position of that centre, and the padding around
//! the charts filled with the colour of the nearest chart texel so mipmaps do not bleed.

use super::ExportError;
use glam::{Vec2, Vec3};
use std::collections::VecDeque;

/// A piece with its texture coordinates and its baked image.
#[derive(Clone, Debug)]
pub struct PieceAtlas {
    /// Vertex positions in the mesh's object space (the unit cube); vertices on chart seams
    /// are repeated, one per chart.
    pub positions: Vec<Vec3>,
    /// Texture coordinates in [0, 1], (0, 0) at the image's first row and column, as glTF
    /// reads them (OBJ's v is 1 − v).
    pub uvs: Vec<Vec2>,
    /// Triangles, in the piece's order and winding.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: a cap face made by a cut.
    pub interior: Vec<bool>,
    /// Image width in texels.
    pub width: u32,
    /// Image height in texels.
    pub height: u32,
    /// sRGB colours, row-major from the first row, RGBA8 (alpha 255).
    pub pixels: Vec<u8>,
    /// Charts the unwrap made.
    pub charts: u32,
    /// Texels whose centre lies on a chart (each got the matter at that point).
    pub covered: usize,
    /// Covered texels where the store holds nothing (painted magenta, as the path tracer
    /// shows such a point).
    pub holes: usize,
}

/// For each covered texel: its index, the object position of its centre and the geometric
/// normal of the triangle it lies on.
pub(crate) struct TexelPoints {
    pub texels: Vec<usize>,
    pub points: Vec<Vec3>,
    pub normals: Vec<Vec3>,
}

/// Unwraps a piece at `texels_per_unit` texels per unit of object space with `padding` (a
/// power of two, 2^k) free texels around every chart: charts are at least 2^(k+1) apart, so
/// no block of 2^k texels (one texel of mip level k) holds texels of two charts once the
/// padding repeats each chart's border. Cap faces and the outer surface never share a chart.
pub(crate) fn unwrap(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    interior: &[bool],
    texels_per_unit: f32,
    padding: u32,
) -> Result<PieceAtlas, ExportError> {
    let flat: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
    let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
    let materials: Vec<u32> = interior.iter().map(|&i| u32::from(i)).collect();
    let mut input = uvunwrap::MeshInput::new(&flat, &indices);
    input.face_materials = Some(&materials);
    let options = uvunwrap::Options {
        density: uvunwrap::Density::Fixed {
            texels_per_unit,
            page_size: None,
        },
        padding,
        ..Default::default()
    };
    let atlas =
        uvunwrap::generate(&[input], &options).map_err(|e| ExportError::Unwrap(e.to_string()))?;
    let mesh = &atlas.meshes[0];
    if atlas.page_count != 1 {
        return Err(ExportError::Unwrap(format!(
            "{} atlas pages where one was asked for",
            atlas.page_count
        )));
    }
    // Sizes rounded up to whole blocks of `padding` (2^k) texels, so that each of the k mip
    // levels halves the image exactly; the coordinates shrink to keep every texel in place.
    let round = |n: u32| n.div_ceil(padding) * padding;
    let (width, height) = (round(atlas.width), round(atlas.height));
    let shrink = Vec2::new(
        atlas.width as f32 / width as f32,
        atlas.height as f32 / height as f32,
    );
    let triangles: Vec<[u32; 3]> = mesh
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    Ok(PieceAtlas {
        positions: mesh
            .vertices
            .iter()
            .map(|v| positions[v.xref as usize])
            .collect(),
        uvs: mesh
            .vertices
            .iter()
            .map(|v| Vec2::from(v.uv) * shrink)
            .collect(),
        interior: interior.to_vec(),
        triangles,
        width,
        height,
        pixels: vec![0; width as usize * height as usize * 4],
        charts: atlas.chart_count,
        covered: 0,
        holes: 0,
    })
}

/// Barycentric coordinates of `p` in the triangle `a b c` (2D), `None` for a degenerate one.
pub fn barycentric(p: Vec2, a: Vec2, b: Vec2, c: Vec2) -> Option<Vec3> {
    let area = (b - a).perp_dot(c - a);
    if area.abs() < 1e-12 {
        return None;
    }
    let wb = (p - a).perp_dot(c - a) / area;
    let wc = (b - a).perp_dot(p - a) / area;
    Some(Vec3::new(1.0 - wb - wc, wb, wc))
}

impl PieceAtlas {
    /// The texels whose centre lies on a triangle (the first triangle that holds it, in
    /// order), with the object position of that centre and the triangle's normal.
    pub(crate) fn texel_points(&self) -> TexelPoints {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut taken = vec![false; w * h];
        let mut out = TexelPoints {
            texels: Vec::new(),
            points: Vec::new(),
            normals: Vec::new(),
        };
        let size = Vec2::new(self.width as f32, self.height as f32);
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| self.uvs[i as usize] * size);
            let [pa, pb, pc] = tri.map(|i| self.positions[i as usize]);
            let normal = (pb - pa).cross(pc - pa).normalize_or_zero();
            let lo = a.min(b).min(c).floor().max(Vec2::ZERO);
            let hi = a.max(b).max(c).ceil().min(size);
            for y in lo.y as usize..hi.y as usize {
                for x in lo.x as usize..hi.x as usize {
                    let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    let Some(l) = barycentric(centre, a, b, c) else {
                        continue;
                    };
                    if l.min_element() < 0.0 || taken[y * w + x] {
                        continue;
                    }
                    taken[y * w + x] = true;
                    out.texels.push(y * w + x);
                    out.points.push(pa * l.x + pb * l.y + pc * l.z);
                    out.normals.push(normal);
                }
            }
        }
        out
    }

    /// Writes the colours of the covered texels (sRGB in [0, 1]; `None` paints magenta and
    /// counts a hole), then fills every other texel with the colour of its nearest covered
    /// texel (breadth first over 4-neighbours), so the padding repeats each chart's border.
    pub(crate) fn paint(&mut self, texels: &[usize], colours: &[Option<Vec3>]) {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut done = vec![false; w * h];
        let mut queue = VecDeque::with_capacity(texels.len());
        self.holes = 0;
        for (&t, c) in texels.iter().zip(colours) {
            let rgb = c.unwrap_or_else(|| {
                self.holes += 1;
                Vec3::new(1.0, 0.0, 1.0)
            });
            let bytes = (rgb.clamp(Vec3::ZERO, Vec3::ONE) * 255.0).round();
            self.pixels[4 * t..4 * t + 4].copy_from_slice(&[
                bytes.x as u8,
                bytes.y as u8,
                bytes.z as u8,
                255,
            ]);
            done[t] = true;
            queue.push_back(t);
        }
        self.covered = texels.len();
        while let Some(t) = queue.pop_front() {
            let (x, y) = (t % w, t / w);
            let neighbours = [
                (x > 0).then(|| t - 1),
                (x + 1 < w).then(|| t + 1),
                (y > 0).then(|| t - w),
                (y + 1 < h).then(|| t + w),
            ];
            for n in neighbours.into_iter().flatten() {
                if !done[n] {
                    done[n] = true;
                    self.pixels.copy_within(4 * t..4 * t + 4, 4 * n);
                    queue.push_back(n);
                }
            }
        }
    }
}
