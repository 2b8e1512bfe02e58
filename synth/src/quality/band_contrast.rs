//! How much contrast each band of the Laplacian pyramid holds against the exemplar's: the
//! direction that the SWD's per-band ratio does not give. A band's SWD ratio above 1 may be
//! detail lost (a smoother image) or detail added (grain, speckle); the band contrast is
//! below 1 for the first and above 1 for the second.

use super::image::LinearImage;
use super::swd::SWD_BANDS;

/// Standard deviation of the luminance of each band of `image`'s Laplacian pyramid, finest
/// first (the bands of the SWD: [`SWD_BANDS`] of them, the last the coarsest octave itself);
/// NaN for a band the image is too small to have.
pub fn band_deviations(image: &LinearImage) -> [f64; SWD_BANDS] {
    let bands = image.laplacian(SWD_BANDS);
    std::array::from_fn(|b| match bands.get(b) {
        Some(band) if band.width * band.height > 1 => deviation(&band.luminance()),
        _ => f64::NAN,
    })
}

/// Each band's deviation in `image` over the exemplar's (`exemplar`, from [`band_deviations`]):
/// 1 as much contrast as the material at that scale, below 1 smoother, above 1 grainier.
pub fn band_contrast(image: &LinearImage, exemplar: &[f64; SWD_BANDS]) -> [f64; SWD_BANDS] {
    let own = band_deviations(image);
    std::array::from_fn(|b| own[b] / exemplar[b])
}

fn deviation(values: &[f32]) -> f64 {
    let n = values.len() as f64;
    let mean = values.iter().map(|&v| v as f64).sum::<f64>() / n;
    (values
        .iter()
        .map(|&v| (v as f64 - mean).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noise(w: usize, h: usize, seed: u32, amplitude: f32) -> LinearImage {
        let mut state = seed;
        let pixels = (0..w * h)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let v = 0.5 + amplitude * ((state >> 8) as f32 / (1u32 << 24) as f32 - 0.5);
                [v, v, v]
            })
            .collect();
        LinearImage {
            width: w,
            height: h,
            pixels,
        }
    }

    #[test]
    fn the_same_image_has_contrast_one_and_more_noise_more_in_the_fine_band() {
        let a = noise(64, 64, 1, 0.2);
        let own = band_deviations(&a);
        assert!(own.iter().all(|d| d.is_finite() && *d > 0.0), "{own:?}");
        let same = band_contrast(&a, &own);
        assert!(same.iter().all(|&c| (c - 1.0).abs() < 1e-12), "{same:?}");
        let louder = band_contrast(&noise(64, 64, 2, 0.4), &own);
        assert!(louder[0] > 1.8 && louder[0] < 2.2, "{louder:?}");
    }
}
