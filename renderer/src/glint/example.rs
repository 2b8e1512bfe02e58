//! The example normal map of a glint microstructure: a square, power-of-two grid of 2D normals
//! (n_x, n_y; n_z is implicit), read with bilinear interpolation so that every point has a
//! normal and a Jacobian, and so that the normals over a square of the example lie between the
//! minimum and maximum of the texels it touches (what the range table stores).

use super::error::GlintError;
use glam::{Mat2, Vec2};
use lazysolid_synth::{
    crop, plan_map, resample_lanczos3_f32, Border, ChannelLayout, ExemplarFit, MAX_DECODE_SIDE,
};
use std::path::Path;

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

/// How a map file became its example: the crop and resample of [`ExemplarFit`] (the rule of
/// exemplars, with the example's limits [`MIN_EXAMPLE_EDGE`] and [`MAX_EXAMPLE_EDGE`]), and
/// for a height map resampled to another scale, the factor its heights were multiplied by so
/// that its slopes (heights are in texel units) stay those of the file.
#[derive(Clone, Debug, PartialEq)]
pub struct MapFit {
    /// The file's size and channels, and the crop and resample applied.
    pub fit: ExemplarFit,
    /// The factor on the heights of a resampled height map.
    pub height_factor: Option<f32>,
}

impl std::fmt::Display for MapFit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.fit)?;
        if let Some(k) = self.height_factor {
            write!(f, ", heights x{k:.4} (slopes kept)")?;
        }
        Ok(())
    }
}

/// A map file decoded to `C` float channels, cut and resampled by the exemplar rule.
struct FittedMap<const C: usize> {
    side: usize,
    texels: Vec<[f32; C]>,
    fit: ExemplarFit,
}

/// Reads `file` as `C` channels (`prepare` turns the decoded image into them, row by row) and
/// fits it to a square power-of-two edge in [`MIN_EXAMPLE_EDGE`]..=[`MAX_EXAMPLE_EDGE`]: the
/// centre square of the largest power of two when that loses at most a quarter of the side,
/// otherwise the square resampled (Lanczos3, wrapping: maps tile) to the nearest power of two.
/// The size is checked from the header before the pixels are decoded.
fn read_fitted<const C: usize>(
    file: &Path,
    what: &str,
    prepare: impl FnOnce(&image::DynamicImage) -> Vec<[f32; C]>,
) -> Result<FittedMap<C>, String> {
    let name = file.display().to_string();
    let reader = || {
        image::ImageReader::open(file)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| format!("{name}: cannot read the {what}: {e}"))
    };
    let (w, h) = reader()?
        .into_dimensions()
        .map_err(|e| format!("{name}: cannot read the {what}: {e}"))?;
    if w.max(h) > MAX_DECODE_SIDE {
        return Err(format!(
            "{name}: the {what} is {w}x{h} texels; at most {MAX_DECODE_SIDE} a side is read"
        ));
    }
    let plan = plan_map(w, h, MIN_EXAMPLE_EDGE as u32, MAX_EXAMPLE_EDGE as u32)
        .map_err(|e| format!("{name}: {e}"))?;
    let image = reader()?
        .decode()
        .map_err(|e| format!("{name}: cannot read the {what}: {e}"))?;
    let channels = u32::from(image.color().channel_count());
    let layout = ChannelLayout::from_channels(channels)
        .ok_or_else(|| format!("{name}: the {what} has {channels} channels; 1 to 4 are read"))?;
    let fit = ExemplarFit {
        name: file
            .file_name()
            .map_or_else(|| name.clone(), |n| n.to_string_lossy().into_owned()),
        size: [w, h],
        layout,
        plan,
    };
    let mut texels = prepare(&image);
    let (mut width, mut height) = (w, h);
    if let Some(c) = plan.crop {
        texels = crop(&texels, width, c);
        (width, height) = (c.width, c.height);
    }
    if let Some([rw, rh]) = plan.resample {
        texels = resample_lanczos3_f32(&texels, width, height, rw, rh, Border::Wrap);
        width = rw;
    }
    debug_assert_eq!(texels.len(), (width * width) as usize);
    Ok(FittedMap {
        side: width as usize,
        texels,
        fit,
    })
}

/// Reads a tangent-space normal map (PNG or any format the `image` crate reads, 8 or 16 bits
/// per channel): n_x = 2 r − 1, n_y = 2 g − 1 (blue is implied by them). A map of any size and
/// aspect is fitted to a square power-of-two edge as an exemplar is ([`MapFit`] says how);
/// resampling filters the unit normals and normalizes the result. The message of an error
/// names the file and, for a bad texel, its column, row and the limit.
///
/// # Errors
/// An unreadable file, a side under [`MIN_EXAMPLE_EDGE`] or over
/// [`MAX_DECODE_SIDE`], or a texel whose (n_x, n_y) leaves the unit disc.
pub fn load_normal_map(file: &Path) -> Result<(NormalExample, MapFit), String> {
    let name = file.display().to_string();
    let mut outside = None;
    let map = read_fitted(file, "normal map", |image| {
        let rgb = image.to_rgb32f();
        let (w, _) = rgb.dimensions();
        rgb.pixels()
            .enumerate()
            .map(|(i, p)| {
                let (nx, ny) = (2.0 * p[0] - 1.0, 2.0 * p[1] - 1.0);
                let n = Vec2::new(nx, ny);
                if (!n.is_finite() || n.length_squared() > 1.0) && outside.is_none() {
                    outside = Some((i as u32 % w, i as u32 / w, nx, ny));
                }
                [nx, ny, (1.0 - n.length_squared()).max(0.0).sqrt()]
            })
            .collect()
    })?;
    if let Some((x, y, nx, ny)) = outside {
        return Err(GlintError::Texel {
            source_name: name,
            x: x as usize,
            y: y as usize,
            nx,
            ny,
        }
        .to_string());
    }
    let resampled = map.fit.plan.resample.is_some();
    let texels = map
        .texels
        .iter()
        .map(|&[x, y, z]| {
            let n = glam::Vec3::new(x, y, z);
            let n = if resampled {
                n.try_normalize().unwrap_or(glam::Vec3::Z)
            } else {
                n
            };
            Vec2::new(n.x, n.y)
        })
        .collect();
    let example =
        NormalExample::from_normals(&name, map.side, texels).map_err(|e| e.to_string())?;
    Ok((
        example,
        MapFit {
            fit: map.fit,
            height_factor: None,
        },
    ))
}

/// Reads a height map (its luminance in [0, 1] times `height_scale`, in texel units), fits it
/// as [`load_normal_map`] fits a normal map (the heights of a resampled map are scaled with
/// its texels, so its slopes are kept), and converts it to normals as
/// [`NormalExample::from_heights`] does.
///
/// # Errors
/// As [`load_normal_map`], for an unreadable file or a bad size.
pub fn load_height_map(file: &Path, height_scale: f32) -> Result<(NormalExample, MapFit), String> {
    let name = file.display().to_string();
    let map = read_fitted(file, "height map", |image| {
        image.to_luma32f().pixels().map(|p| [p[0]]).collect()
    })?;
    // Heights are in texel units: a map resampled from `s` to `t` texels a side has slopes
    // `s / t` times as steep unless its heights grow by `t / s`.
    let height_factor = map.fit.plan.resample.map(|[t, _]| {
        let s = map
            .fit
            .plan
            .crop
            .map_or(map.fit.size[0].min(map.fit.size[1]), |c| c.width);
        t as f32 / s as f32
    });
    let k = height_scale * height_factor.unwrap_or(1.0);
    let heights: Vec<f32> = map.texels.iter().map(|[h]| h * k).collect();
    let example =
        NormalExample::from_heights(&name, map.side, &heights).map_err(|e| e.to_string())?;
    Ok((
        example,
        MapFit {
            fit: map.fit,
            height_factor,
        },
    ))
}
