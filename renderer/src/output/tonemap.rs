//! The display transform from linear HDR radiance to 8-bit sRGB: exposure, a tone curve, the
//! sRGB transfer function and rounding.

/// The tone curve applied after exposure, per channel unless stated.
///
/// All three map 0 to 0 and never exceed 1, so the sRGB step that follows always gets 0..1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Operator {
    /// `min(x, 1)`: exact for images already in 0..1 (reference comparisons, albedo checks);
    /// highlights above 1 clip.
    #[default]
    Clamp,
    /// `x / (1 + x)`: compresses every value into 0..1 without clipping, at the cost of
    /// darkening mid-tones (1 becomes 0.5). `+inf` becomes 1.
    Reinhard,
    /// Stephen Hill's fit of the ACES reference rendering and output transforms: a film-like
    /// shoulder and slight desaturation of highlights. On linear sRGB `c`:
    /// `v = M_in c`, `w = (v (v + 0.0245786) - 0.000090537) / (v (0.983729 v + 0.432951) +
    /// 0.238081)` per channel, `out = clamp(M_out w, 0, 1)`, where `M_in` maps sRGB to the ACES
    /// fit space (rows 0.59719 0.35458 0.04823 / 0.07600 0.90834 0.01566 / 0.02840 0.13383
    /// 0.83777) and `M_out` maps back (rows 1.60475 -0.53108 -0.07367 / -0.10208 1.10813
    /// -0.00605 / -0.00327 -0.07276 1.07602).
    AcesFitted,
}

/// How linear radiance becomes displayable: `operator(radiance * 2^exposure_ev)`, then the sRGB
/// OETF, then rounding to the nearest 8-bit code.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToneMap {
    /// Exposure in stops: +1 doubles the radiance before the curve.
    pub exposure_ev: f32,
    /// The tone curve.
    pub operator: Operator,
}

const ACES_IN: [[f32; 3]; 3] = [
    [0.59719, 0.35458, 0.04823],
    [0.07600, 0.90834, 0.01566],
    [0.02840, 0.13383, 0.83777],
];

const ACES_OUT: [[f32; 3]; 3] = [
    [1.60475, -0.53108, -0.07367],
    [-0.10208, 1.10813, -0.00605],
    [-0.00327, -0.07276, 1.07602],
];

fn mul(m: &[[f32; 3]; 3], c: [f32; 3]) -> [f32; 3] {
    m.map(|row| row[0] * c[0] + row[1] * c[1] + row[2] * c[2])
}

fn aces_curve(v: f32) -> f32 {
    if v > 1e15 {
        // The curve is within 1e-15 of its limit 1 / 0.983729 here; evaluating it would overflow
        // to inf / inf = NaN.
        return 1.0 / 0.983729;
    }
    (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.432951) + 0.238081)
}

impl ToneMap {
    /// Linear radiance to display-linear 0..1 (exposure and curve, before the sRGB OETF).
    ///
    /// Negative components (possible after reconstruction filters with negative lobes) are
    /// treated as 0; NaN stays NaN so that the caller can refuse it.
    pub fn apply(&self, c: [f32; 3]) -> [f32; 3] {
        let scale = self.exposure_ev.exp2();
        let c = c.map(|x| if x < 0.0 { 0.0 } else { x * scale });
        match self.operator {
            Operator::Clamp => c.map(|x| if x > 1.0 { 1.0 } else { x }),
            Operator::Reinhard => c.map(|x| {
                if x == f32::INFINITY {
                    1.0
                } else {
                    x / (1.0 + x)
                }
            }),
            Operator::AcesFitted => mul(&ACES_OUT, mul(&ACES_IN, c).map(aces_curve)).map(|x| {
                if x.is_nan() {
                    x
                } else {
                    x.clamp(0.0, 1.0)
                }
            }),
        }
    }

    /// Linear radiance to 8-bit sRGB codes; `None` when a component is NaN (no code shows it).
    pub fn to_srgb8(&self, c: [f32; 3]) -> Option<[u8; 3]> {
        let d = self.apply(c);
        if d.iter().any(|x| x.is_nan()) {
            return None;
        }
        Some(d.map(encode8))
    }
}

/// The sRGB opto-electronic transfer function (IEC 61966-2-1) on 0..1: linear `x` to the
/// encoded value a display expects, `12.92 x` up to 0.0031308, else `1.055 x^(1/2.4) - 0.055`.
pub fn srgb_oetf(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1), the inverse of [`srgb_oetf`]:
/// an encoded value on 0..1 to linear, `x / 12.92` up to 0.04045, else `((x + 0.055) / 1.055)^2.4`.
pub fn srgb_eotf(x: f32) -> f32 {
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// Display-linear 0..1 to the nearest 8-bit sRGB code.
pub(crate) fn encode8(x: f32) -> u8 {
    (srgb_oetf(x.clamp(0.0, 1.0)) * 255.0).round() as u8
}
