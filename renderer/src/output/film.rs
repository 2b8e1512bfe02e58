//! The film: the per-pixel result of a render, before any display transform.

use super::OutputError;

/// A rendered image and its optional auxiliary (AOV) layers, all row-major with the top row
/// first, all `width * height` long.
///
/// The fields are private so that every film that exists has consistent layer lengths: the
/// writers can then index without re-checking and never panic.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    color: Vec<[f32; 3]>,
    albedo: Option<Vec<[f32; 3]>>,
    normal: Option<Vec<[f32; 3]>>,
    depth: Option<Vec<f32>>,
}

impl Film {
    /// A film from its linear HDR radiance (linear Rec.709/sRGB primaries, unbounded).
    ///
    /// # Errors
    /// A zero width or height, a size whose pixel count overflows, or `color.len()` other than
    /// `width * height`.
    pub fn new(width: u32, height: u32, color: Vec<[f32; 3]>) -> Result<Film, OutputError> {
        let expected = pixel_count(width, height)?;
        check_len("color", width, height, expected, color.len())?;
        Ok(Film {
            width,
            height,
            color,
            albedo: None,
            normal: None,
            depth: None,
        })
    }

    /// An all-black film, the starting point of an accumulating integrator.
    ///
    /// # Errors
    /// As [`Film::new`].
    pub fn black(width: u32, height: u32) -> Result<Film, OutputError> {
        let n = pixel_count(width, height)?;
        Film::new(width, height, vec![[0.0; 3]; n])
    }

    /// Adds the first-hit albedo layer (linear reflectance in 0..1), which denoisers use to keep
    /// texture detail.
    ///
    /// # Errors
    /// A length other than `width * height`.
    pub fn with_albedo(mut self, albedo: Vec<[f32; 3]>) -> Result<Film, OutputError> {
        check_len("albedo", self.width, self.height, self.len(), albedo.len())?;
        self.albedo = Some(albedo);
        Ok(self)
    }

    /// Adds the first-hit world-space shading normal layer (components in -1..1; zero where
    /// nothing was hit).
    ///
    /// # Errors
    /// A length other than `width * height`.
    pub fn with_normal(mut self, normal: Vec<[f32; 3]>) -> Result<Film, OutputError> {
        check_len("normal", self.width, self.height, self.len(), normal.len())?;
        self.normal = Some(normal);
        Ok(self)
    }

    /// Adds the first-hit distance layer (distance from the camera along the ray, `+inf` where
    /// nothing was hit).
    ///
    /// # Errors
    /// A length other than `width * height`.
    pub fn with_depth(mut self, depth: Vec<f32>) -> Result<Film, OutputError> {
        check_len("depth", self.width, self.height, self.len(), depth.len())?;
        self.depth = Some(depth);
        Ok(self)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// `width * height`, the length of every layer.
    pub fn len(&self) -> usize {
        self.color.len()
    }

    /// Always false: a film has at least one pixel (kept for the `len`/`is_empty` convention).
    pub fn is_empty(&self) -> bool {
        self.color.is_empty()
    }

    /// Linear HDR radiance, row-major, top row first.
    pub fn color(&self) -> &[[f32; 3]] {
        &self.color
    }

    /// Mutable radiance, for integrators that accumulate in place; a slice, so the length that
    /// the other layers rely on cannot change.
    pub fn color_mut(&mut self) -> &mut [[f32; 3]] {
        &mut self.color
    }

    /// The albedo layer, when the renderer produced one.
    pub fn albedo(&self) -> Option<&[[f32; 3]]> {
        self.albedo.as_deref()
    }

    /// The world-space normal layer, when the renderer produced one.
    pub fn normal(&self) -> Option<&[[f32; 3]]> {
        self.normal.as_deref()
    }

    /// The distance layer, when the renderer produced one.
    pub fn depth(&self) -> Option<&[f32]> {
        self.depth.as_deref()
    }
}

fn pixel_count(width: u32, height: u32) -> Result<usize, OutputError> {
    if width == 0 || height == 0 {
        return Err(OutputError::EmptyFilm { width, height });
    }
    (width as usize)
        .checked_mul(height as usize)
        .ok_or(OutputError::FilmTooLarge { width, height })
}

fn check_len(
    layer: &'static str,
    width: u32,
    height: u32,
    expected: usize,
    actual: usize,
) -> Result<(), OutputError> {
    if actual == expected {
        Ok(())
    } else {
        Err(OutputError::LayerLength {
            layer,
            width,
            height,
            expected,
            actual,
        })
    }
}
