//! The example normal map of a glint microstructure: a square, power-of-two grid of 2D normals
//! (n_x, n_y; n_z is implicit), read with bilinear interpolation so that every point has a
//! normal and a Jacobian, and so that the normals over a square of the example lie between the
//! minimum and maximum of the texels it touches (what the range table stores).

use super::error::GlintError;
use glam::{Mat2, Vec2};

/// Smallest example edge: a quarter of it (the largest target patch) must still be 2 texels.
pub const MIN_EXAMPLE_EDGE: usize = 8;
/// Largest example edge: its range table (levels up to a quarter edge, 8 bytes an entry) stays
/// under 160 MiB at this size.
pub const MAX_EXAMPLE_EDGE: usize = 2048;

/// A square example normal map; texel (x, y) sits at the integer point (x, y) of example space.
#[derive(Clone, Debug)]
pub struct NormalExample {
    size: usize,
    texels: Vec<Vec2>,
}

impl NormalExample {
    /// An example from `size`² normals, row by row (`texels[y * size + x]`). `source_name`
    /// (a file or a description) names the example in errors.
    ///
    /// # Errors
    /// [`GlintError::Size`] for a non-square or out-of-range edge, [`GlintError::Texel`] for a
    /// normal that is not finite or outside the unit disc.
    pub fn from_normals(
        source_name: &str,
        size: usize,
        texels: Vec<Vec2>,
    ) -> Result<Self, GlintError> {
        check_size(source_name, size, texels.len())?;
        for (i, n) in texels.iter().enumerate() {
            if !n.is_finite() || n.length_squared() > 1.0 {
                return Err(GlintError::Texel {
                    source_name: source_name.into(),
                    x: i % size,
                    y: i / size,
                    nx: n.x,
                    ny: n.y,
                });
            }
        }
        Ok(NormalExample { size, texels })
    }

    /// An example from a height field (`heights[y * size + x]`, in texel units), by central
    /// differences with wrap-around: n ∝ (−∂h/∂x, −∂h/∂y, 1).
    ///
    /// # Errors
    /// As [`NormalExample::from_normals`], and [`GlintError::Height`] for a height that is
    /// not finite.
    pub fn from_heights(
        source_name: &str,
        size: usize,
        heights: &[f32],
    ) -> Result<Self, GlintError> {
        check_size(source_name, size, heights.len())?;
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(GlintError::Height {
                source_name: source_name.into(),
                x: i % size,
                y: i / size,
                value: heights[i],
            });
        }
        let h = |x: usize, y: usize| heights[(y % size) * size + x % size];
        let texels = (0..size * size)
            .map(|i| {
                let (x, y) = (i % size, i / size);
                let dx = 0.5 * (h(x + 1, y) - h(x + size - 1, y));
                let dy = 0.5 * (h(x, y + 1) - h(x, y + size - 1));
                let n = glam::Vec3::new(-dx, -dy, 1.0).normalize();
                Vec2::new(n.x, n.y)
            })
            .collect();
        Self::from_normals(source_name, size, texels)
    }

    /// Edge in texels.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The texels, row by row.
    pub fn texels(&self) -> &[Vec2] {
        &self.texels
    }

    /// The texel at column `x`, row `y`.
    pub fn texel(&self, x: usize, y: usize) -> Vec2 {
        self.texels[y * self.size + x]
    }

    /// The mean normal (x and y): the constant Ī of variance-preserving blending, global so
    /// that the blend stays monotone in every input.
    pub fn mean(&self) -> Vec2 {
        let sum = self
            .texels
            .iter()
            .fold(glam::DVec2::ZERO, |s, n| s + n.as_dvec2());
        (sum / self.texels.len() as f64).as_vec2()
    }

    /// The bilinearly interpolated normal at `p` (0 ≤ p < size − 1 per axis) and its Jacobian
    /// (columns ∂/∂x and ∂/∂y). Twin of `glint_example_sample` in `glint/by_example.glsl`.
    pub fn sample(&self, p: Vec2) -> (Vec2, Mat2) {
        let (x0, y0) = (p.x.floor(), p.y.floor());
        let (tx, ty) = (p.x - x0, p.y - y0);
        let (x, y) = (x0 as usize, y0 as usize);
        let t00 = self.texel(x, y);
        let t10 = self.texel(x + 1, y);
        let t01 = self.texel(x, y + 1);
        let t11 = self.texel(x + 1, y + 1);
        let bottom = t00 + (t10 - t00) * tx;
        let top = t01 + (t11 - t01) * tx;
        let n = bottom + (top - bottom) * ty;
        let d_dx = (t10 - t00) + ((t11 - t01) - (t10 - t00)) * ty;
        let d_dy = top - bottom;
        (n, Mat2::from_cols(d_dx, d_dy))
    }
}

fn check_size(source_name: &str, size: usize, texels: usize) -> Result<(), GlintError> {
    if !size.is_power_of_two()
        || !(MIN_EXAMPLE_EDGE..=MAX_EXAMPLE_EDGE).contains(&size)
        || texels != size * size
    {
        return Err(GlintError::Size {
            source_name: source_name.into(),
            width: size,
            height: texels.checked_div(size).unwrap_or(0),
            texels,
            min: MIN_EXAMPLE_EDGE,
            max: MAX_EXAMPLE_EDGE,
        });
    }
    Ok(())
}

/// Reads a tangent-space normal map (PNG or any format the `image` crate reads, 8 or 16 bits
/// per channel): n_x = 2 r − 1, n_y = 2 g − 1 (blue is implied by them). The message of an
/// error names the file and, for a bad texel, its column, row and the limit.
///
/// # Errors
/// An unreadable file, a non-square or non-power-of-two image (edge from
/// [`MIN_EXAMPLE_EDGE`] to [`MAX_EXAMPLE_EDGE`]), or a texel whose (n_x, n_y) leaves the unit
/// disc.
pub fn load_normal_map(file: &std::path::Path) -> Result<NormalExample, String> {
    let name = file.display().to_string();
    let image = image::open(file)
        .map_err(|e| format!("{name}: cannot read the normal map: {e}"))?
        .to_rgb32f();
    let (w, h) = image.dimensions();
    check_size(&name, w as usize, (w as usize) * (h as usize)).map_err(|e| e.to_string())?;
    let texels = image
        .pixels()
        .map(|p| Vec2::new(2.0 * p[0] - 1.0, 2.0 * p[1] - 1.0))
        .collect();
    NormalExample::from_normals(&name, w as usize, texels).map_err(|e| e.to_string())
}

/// Reads a height map (its luminance in [0, 1] times `height_scale`, in texel units) and
/// converts it to normals as [`NormalExample::from_heights`] does.
///
/// # Errors
/// As [`load_normal_map`], for an unreadable file or a bad size.
pub fn load_height_map(file: &std::path::Path, height_scale: f32) -> Result<NormalExample, String> {
    let name = file.display().to_string();
    let image = image::open(file)
        .map_err(|e| format!("{name}: cannot read the height map: {e}"))?
        .to_luma32f();
    let (w, h) = image.dimensions();
    check_size(&name, w as usize, (w as usize) * (h as usize)).map_err(|e| e.to_string())?;
    let heights: Vec<f32> = image.pixels().map(|p| p[0] * height_scale).collect();
    NormalExample::from_heights(&name, w as usize, &heights).map_err(|e| e.to_string())
}
