//! The environment on the CPU: texels and the importance-sampling tables of a lat-long map (or a
//! constant), built once from the scene and shared by the GPU upload and the CPU reference.

use super::error::ShadingError;
use crate::scene::Environment;
use crate::shader_constants::{ENVIRONMENT_CONSTANT, ENVIRONMENT_LATLONG};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Most texels a map may have: indices of the RGB data stay far below 2³², and the float CDFs
/// keep enough resolution per texel.
pub const MAX_ENVIRONMENT_TEXELS: u64 = 1 << 26;

/// An environment ready to be evaluated and sampled.
///
/// A lat-long map is sampled through a piecewise-constant 2D distribution over its texels,
/// proportional to luminance × sin θ (the solid angle a texel covers): a marginal CDF over rows
/// and one conditional CDF per row. The per-texel density `pdf` is derived from the stored
/// (float) CDFs themselves, so that it is exactly the probability with which sampling picks a
/// texel, divided by the texel's area in the unit square.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentMap {
    /// Where the map came from (empty for a constant), for messages.
    pub source: PathBuf,
    /// `ENVIRONMENT_*` of `shader_constants`.
    pub kind: u32,
    /// Radiance of a constant environment.
    pub radiance: Vec3,
    /// Multiplier of the map's texels.
    pub intensity: f32,
    /// cos of the rotation about +y.
    pub rotation_cos: f32,
    /// sin of the rotation about +y.
    pub rotation_sin: f32,
    /// Width in texels (0 for a constant).
    pub width: u32,
    /// Height in texels (0 for a constant).
    pub height: u32,
    /// RGB texels, row by row from the top (+y).
    pub texels: Vec<f32>,
    /// Density over the unit square of (u, v), per texel.
    pub pdf: Vec<f32>,
    /// CDF over rows: `height + 1` values from 0 to 1.
    pub marginal_cdf: Vec<f32>,
    /// CDF over the columns of each row: `height` runs of `width + 1` values from 0 to 1.
    pub conditional_cdf: Vec<f32>,
    /// False when nothing can be sampled (black constant, black map).
    pub sampleable: bool,
}

/// Luminance of linear Rec. 709 RGB: what importance sampling follows.
fn luminance(rgb: [f32; 3]) -> f64 {
    0.2126 * rgb[0] as f64 + 0.7152 * rgb[1] as f64 + 0.0722 * rgb[2] as f64
}

/// Normalized running sums of `values` (`values.len() + 1` entries, last exactly 1); uniform
/// steps when they sum to zero.
fn cdf(values: &[f64]) -> (Vec<f32>, f64) {
    let total: f64 = values.iter().sum();
    let n = values.len();
    let mut out = Vec::with_capacity(n + 1);
    let mut running = 0.0;
    out.push(0.0);
    for (i, v) in values.iter().enumerate() {
        running += v;
        out.push(if total > 0.0 {
            (running / total) as f32
        } else {
            (i + 1) as f32 / n as f32
        });
    }
    out[n] = 1.0;
    (out, total)
}

impl EnvironmentMap {
    /// The same radiance from every direction; black means no environment (nothing to sample).
    pub fn constant(radiance: Vec3) -> Self {
        EnvironmentMap {
            source: PathBuf::new(),
            kind: ENVIRONMENT_CONSTANT,
            radiance,
            intensity: 1.0,
            rotation_cos: 1.0,
            rotation_sin: 0.0,
            width: 0,
            height: 0,
            texels: Vec::new(),
            pdf: Vec::new(),
            marginal_cdf: Vec::new(),
            conditional_cdf: Vec::new(),
            sampleable: radiance.max_element() > 0.0,
        }
    }

    /// Builds the scene's environment, loading the EXR of a lat-long map.
    ///
    /// # Errors
    /// See [`EnvironmentMap::load`].
    pub fn from_scene(environment: &Environment) -> Result<Self, ShadingError> {
        match environment {
            Environment::Constant(radiance) => Ok(Self::constant(*radiance)),
            Environment::LatLong {
                path,
                intensity,
                rotation_deg,
            } => Self::load(path, *intensity, *rotation_deg),
        }
    }

    /// Loads a lat-long HDR map (any format the `image` crate decodes, EXR in practice).
    ///
    /// # Errors
    /// An unreadable or undecodable file, a map of no or too many texels, a negative or
    /// non-finite texel, an intensity that is not finite and > 0, a non-finite rotation; each
    /// naming the file.
    pub fn load(path: &Path, intensity: f32, rotation_deg: f32) -> Result<Self, ShadingError> {
        let image = image::open(path)
            .map_err(|source| ShadingError::Image {
                file: path.to_path_buf(),
                source,
            })?
            .to_rgb32f();
        let (width, height) = image.dimensions();
        Self::from_texels(
            path,
            width,
            height,
            image.into_raw(),
            intensity,
            rotation_deg,
        )
    }

    /// Builds a lat-long map from `width × height` RGB texels (row 0 at the top), as
    /// [`EnvironmentMap::load`] does after decoding; `source` names it in messages.
    ///
    /// # Errors
    /// As [`EnvironmentMap::load`], and a texel count that is not `width × height`.
    pub fn from_texels(
        source: &Path,
        width: u32,
        height: u32,
        texels: Vec<f32>,
        intensity: f32,
        rotation_deg: f32,
    ) -> Result<Self, ShadingError> {
        let file = source.to_path_buf();
        let count = width as u64 * height as u64;
        if count == 0 || count > MAX_ENVIRONMENT_TEXELS || texels.len() as u64 != 3 * count {
            return Err(ShadingError::MapSize {
                file,
                width,
                height,
                limit: MAX_ENVIRONMENT_TEXELS,
            });
        }
        if !(intensity.is_finite() && intensity > 0.0) {
            return Err(ShadingError::Parameter {
                file,
                field: "intensity",
                value: intensity,
                limit: "finite and > 0",
            });
        }
        if !rotation_deg.is_finite() {
            return Err(ShadingError::Parameter {
                file,
                field: "rotation",
                value: rotation_deg,
                limit: "finite (degrees)",
            });
        }
        if let Some(i) = texels.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            let t = i / 3;
            return Err(ShadingError::Texel {
                file,
                x: (t % width as usize) as u32,
                y: (t / width as usize) as u32,
                value: format!("{:?}", &texels[3 * t..3 * t + 3]),
            });
        }
        let (w, h) = (width as usize, height as usize);
        let mut conditional_cdf = Vec::with_capacity(h * (w + 1));
        let mut row_sums = Vec::with_capacity(h);
        let mut row = vec![0.0f64; w];
        for y in 0..h {
            let sin_theta = (std::f64::consts::PI * (y as f64 + 0.5) / h as f64).sin();
            for (x, f) in row.iter_mut().enumerate() {
                let i = 3 * (y * w + x);
                *f = luminance([texels[i], texels[i + 1], texels[i + 2]]) * sin_theta;
            }
            let (c, sum) = cdf(&row);
            conditional_cdf.extend_from_slice(&c);
            row_sums.push(sum);
        }
        let (marginal_cdf, total) = cdf(&row_sums);
        let mut pdf = Vec::with_capacity(w * h);
        for y in 0..h {
            let py = (marginal_cdf[y + 1] as f64 - marginal_cdf[y] as f64) * h as f64;
            let c = &conditional_cdf[y * (w + 1)..(y + 1) * (w + 1)];
            for x in 0..w {
                pdf.push((py * (c[x + 1] as f64 - c[x] as f64) * w as f64) as f32);
            }
        }
        let angle = rotation_deg.to_radians();
        Ok(EnvironmentMap {
            source: file,
            kind: ENVIRONMENT_LATLONG,
            radiance: Vec3::ZERO,
            intensity,
            rotation_cos: angle.cos(),
            rotation_sin: angle.sin(),
            width,
            height,
            texels,
            pdf,
            marginal_cdf,
            conditional_cdf,
            sampleable: total > 0.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_follow_luminance_times_sin_theta() {
        // 2x2: only the top-left texel is lit, so only it can be sampled.
        let mut texels = vec![0.0; 12];
        texels[..3].copy_from_slice(&[1.0, 1.0, 1.0]);
        let map = EnvironmentMap::from_texels(Path::new("t.exr"), 2, 2, texels, 2.0, 90.0).unwrap();
        assert_eq!(map.marginal_cdf, vec![0.0, 1.0, 1.0]);
        assert_eq!(&map.conditional_cdf[..3], &[0.0, 1.0, 1.0]);
        // A black row keeps a uniform CDF, so a search never divides by zero.
        assert_eq!(&map.conditional_cdf[3..], &[0.0, 0.5, 1.0]);
        assert_eq!(map.pdf, vec![4.0, 0.0, 0.0, 0.0]);
        assert!(map.sampleable);
        assert!(map.rotation_cos.abs() < 1e-7 && map.rotation_sin == 1.0);
    }

    #[test]
    fn bad_maps_are_rejected_with_the_file() {
        let e =
            EnvironmentMap::from_texels(Path::new("sky.exr"), 1, 1, vec![0.0, -1.0, 0.0], 1.0, 0.0)
                .unwrap_err()
                .to_string();
        assert!(
            e.contains("sky.exr") && e.contains("column 0, row 0"),
            "{e}"
        );
        let e = EnvironmentMap::from_texels(Path::new("sky.exr"), 1, 1, vec![0.0; 3], 0.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("sky.exr") && e.contains("intensity"), "{e}");
        let e = EnvironmentMap::from_texels(Path::new("sky.exr"), 0, 4, vec![], 1.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("0x4"), "{e}");
        let e = EnvironmentMap::load(Path::new("/nonexistent/sky.exr"), 1.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("/nonexistent/sky.exr"), "{e}");
        assert!(!EnvironmentMap::constant(Vec3::ZERO).sampleable);
    }
}
