//! Feature distance (appearance-space synthesis, Lefebvre & Hoppe 2006 §4.2): a signed
//! distance to the exemplar's features, appended to every pixel's colour *before* the
//! neighbourhood analysis, so that an appearance vector knows how far it lies from the nearest
//! crack, vein or outline — farther than its 5×5 neighbourhood sees.
//!
//! **Why.** The 5×5 neighbourhood of a level samples `±2h`; a pixel in the middle of a light
//! blob and one in a light gap between blobs look the same to it, so the correction can grow
//! blobs without outlines or break a crack into fragments. The thesis' solid synthesis adds
//! the feature distance to its appearance space for that reason ("synthesis quality greatly
//! improves", seed 003 §3.5.2.2).
//!
//! **The mask.** The papers take a user-drawn binary mask; lazysolid accepts any photo, so
//! the mask is found: the luminance minus its local mean (a Gaussian of σ = side / 16,
//! which removes lighting gradients and keeps structures up to that size), split in two by
//! Otsu's threshold; the *smaller* class is the feature (dark cracks in light stone, light
//! veins in dark marble — whichever is rare). Where Otsu's cut falls inside a mottled body
//! (its classes within about a pixel of each other, so the channel would be weak or off), the
//! minimum-error threshold (Kittler & Illingworth 1986) is tried instead and taken when its
//! class reaches farther and is connected (thin veins, not a scattered tail of the mottle):
//! marble1's faint light veins, 3.1 % of the pixels, which Otsu's split of the mottle at
//! 46 % lost (128³ SWD ratio 2.95 / 3.04 / 3.23 → 1.49 / 1.52 / 1.66). It is also taken where
//! Otsu's split is no speckle but took part of the body with the structure: when the
//! minimum-error class holds at least [`MIN_STRUCTURE_SHARE`] of the pixels, is connected, and
//! its distance reaches [`MIN_REACH_GAIN`] times as far (stone33's joints, ground1's cracks,
//! brick's mortar, granite1's veins: 9–12 % of the pixels where Otsu's class held 19–27 %;
//! `FeatureMask` forces either split). The signed distance
//! is Euclidean and exact (the separable lower-envelope transform), toroidal when the
//! exemplar tiles, negative inside features, clamped to `±side / 16` (at least 4 pixels; the
//! clamp keeps the medial axes' singularities out, as the paper recommends).
//!
//! **Scale.** The channel is scaled so that its standard deviation is `weight` times the
//! colour's (all three channels together): `weight` 0 leaves the analysis as it was, 1 gives
//! the feature as much say as the colour. A texture without structures (speckle: every pixel
//! within a pixel of a border) gets no channel: below [`SPECKLE_DEVIATION`] pixels of distance
//! deviation the channel is off, ramping to its full weight over [`SPECKLE_RAMP`] pixels.
//! Speckle is switched off rather than weighted like the rest because the channel brought the
//! SWD ratios of structured exemplars (cracked, stone33) far down but raised a speckled one's
//! (slate); a channel proportional to the distance's own spread instead spared slate but lost
//! most of the gain on the others (`docs/solid.md`, "The feature channel and its mask";
//! the figures in `docs/log/solid.md`, "Feature distance"). The synthesized output is colour
//! only; the channel only shapes which neighbourhoods count as alike.

use super::stack::gaussian_blur;

/// Default feature weight, in percent of the colour's standard deviation.
pub const DEFAULT_FEATURE_WEIGHT: u32 = 100;

/// Largest feature weight accepted, in percent: past about 4 the colour's differences are
/// drowned (the paper's "synthesis noise").
pub const MAX_FEATURE_WEIGHT: u32 = 400;

/// Version of the mask and distance rule, part of the solid candidates' cache key: bumped
/// whenever what this module computes changes.
pub const FEATURE_RULE: u32 = 3;

/// Standard deviation of the signed distance, in pixels, at and below which the channel is
/// off: the distance of a speckled texture (slate: 0.66 px) says for almost every pixel only
/// whether it is dark or light, which its colour already says; used as a fourth channel it
/// adds noise, not reach (slate 128³'s SWD ratio rose from 1.8–2.1 to 3.2–3.5).
pub const SPECKLE_DEVIATION: f64 = 0.75;

/// Pixels of deviation over which the channel ramps from off to its full weight.
pub const SPECKLE_RAMP: f64 = 0.5;

/// Bins of the Otsu histogram.
const OTSU_BINS: usize = 256;

/// The feature mask and its scaled signed distance for one image.
#[derive(Clone, Debug)]
pub struct FeatureMap {
    /// Whether each pixel (row-major) is a feature pixel.
    pub mask: Vec<bool>,
    /// The feature channel per pixel: the clamped signed distance in pixels, scaled (see the
    /// module docs); 0 everywhere when the image has no two classes.
    pub channel: Vec<f32>,
    /// The clamped signed distance itself, in pixels (negative inside features), whatever the
    /// weight: what a relief is made of (`crate::relief`); 0 everywhere without two classes.
    pub distance: Vec<f32>,
    /// Whether the features are the dark class (cracks, outlines) or the light one.
    pub dark: bool,
    /// The clamp of the signed distance, in pixels.
    pub clamp: f32,
    /// Standard deviation of the clamped signed distance over the clamp, 0..=1: small for
    /// speckle (every pixel near a border), large for structures.
    pub spread: f64,
    /// Share of the full weight the channel got: 0 for speckle, 1 for structures (see
    /// [`SPECKLE_DEVIATION`]).
    pub reach: f64,
    /// Which threshold split the detail.
    pub rule: Threshold,
}

/// Which threshold finds an image's features.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FeatureMask {
    /// The rule of the module docs: Otsu's split, or the minimum-error one where its class is
    /// a connected structure that reaches clearly farther (or Otsu's is speckle).
    #[default]
    Auto,
    /// Otsu's split always, speckle included: an ablation that shows what the minimum-error
    /// split gains where the rule takes it.
    Otsu,
    /// The minimum-error split always.
    MinimumError,
}

impl FeatureMask {
    /// Its name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            FeatureMask::Auto => "auto",
            FeatureMask::Otsu => "otsu",
            FeatureMask::MinimumError => "minimum-error",
        }
    }

    /// A number for cache keys.
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// Smallest share of the pixels the minimum-error class must hold to replace an Otsu split
/// that is not speckle: cracked's 2.2 % crack shadows, Craters' 1.1 % and crinklepaper's 0.6 %
/// are detail of a structure Otsu already split well (forced, they cost 0.2–0.7 of SWD ratio),
/// while the joints, cells, mortar and veins that gained are 9–12 % (128² fits;
/// `docs/log/solid.md`, "Joints, cells, mortar").
pub const MIN_STRUCTURE_SHARE: f64 = 0.05;

/// How much farther (distance deviation) the minimum-error class must reach than Otsu's to
/// replace a split that is not speckle: where Otsu also cut the body (stone33, ground1, brick,
/// granite1: 19–27 % "features") the minimum-error class reaches 1.36–1.92× as far; where
/// Otsu's class already is the structure (pink_marble's veins, terra's cracks) 1.02–1.05×.
pub const MIN_REACH_GAIN: f64 = 1.25;

/// The threshold that split the local detail into feature and background.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Threshold {
    /// Otsu's (largest between-class variance): the default.
    Otsu,
    /// Kittler and Illingworth's minimum error, where Otsu's split was speckle.
    MinimumError,
}

fn luminance(c: [f32; 3]) -> f32 {
    0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]
}

/// A Gaussian blur of a scalar image (wrapping or clamping at the borders), the stack's.
fn blur(src: &[f32], w: u32, h: u32, sigma: f32, toroidal: bool) -> Vec<f32> {
    let packed: Vec<[f32; 3]> = src.iter().map(|&v| [v, 0.0, 0.0]).collect();
    gaussian_blur(&packed, w, h, sigma, toroidal)
        .into_iter()
        .map(|p| p[0])
        .collect()
}

/// The histogram both thresholds cut: `values` binned into [`OTSU_BINS`] bins over their
/// range, with the value that a cut after bin `i` stands for.
struct Bins {
    counts: [f64; OTSU_BINS],
    lo: f32,
    hi: f32,
}

impl Bins {
    /// `None` when all values are equal (nothing to cut).
    fn of(values: &[f32]) -> Option<Self> {
        let (lo, hi) = values
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if hi - lo <= 1e-6 {
            return None;
        }
        let mut counts = [0f64; OTSU_BINS];
        for &v in values {
            counts[(((v - lo) / (hi - lo)) * (OTSU_BINS - 1) as f32).round() as usize] += 1.0;
        }
        Some(Self { counts, lo, hi })
    }

    /// The threshold between bin `i` and bin `i + 1`: values in bins up to `i` lie below it.
    fn cut(&self, i: usize) -> f32 {
        self.lo + (i as f32 + 0.5) / (OTSU_BINS - 1) as f32 * (self.hi - self.lo)
    }

    /// The sums of the counts weighted by 1, the bin index and its square.
    fn moments(&self) -> (f64, f64, f64) {
        self.counts
            .iter()
            .enumerate()
            .fold((0.0, 0.0, 0.0), |(n, s, q), (i, &c)| {
                (n + c, s + i as f64 * c, q + (i * i) as f64 * c)
            })
    }
}

/// Otsu's threshold of `values`: the cut that maximizes the between-class variance; `None`
/// when all values are equal. Public because a picture's classes are judged by the same cut
/// as the exemplar's (`lazysolid` example `albedo_share`).
pub fn otsu(values: &[f32]) -> Option<f32> {
    let bins = Bins::of(values)?;
    let (n, total, _) = bins.moments();
    let (mut below, mut below_sum) = (0.0f64, 0.0f64);
    let mut best = (f64::NEG_INFINITY, 0usize);
    for (i, &c) in bins.counts.iter().enumerate().take(OTSU_BINS - 1) {
        below += c;
        below_sum += i as f64 * c;
        let above = n - below;
        if below == 0.0 || above == 0.0 {
            continue;
        }
        let mean_below = below_sum / below;
        let mean_above = (total - below_sum) / above;
        let between = below * above * (mean_below - mean_above).powi(2);
        if between > best.0 {
            best = (between, i);
        }
    }
    Some(bins.cut(best.1))
}

/// Kittler and Illingworth's minimum-error threshold of `values`: the cut that minimizes the
/// classification error of a two-Gaussian fit, which (unlike Otsu's) finds a small class of
/// its own spread beside a large one; `None` when all values are equal or no cut fits.
fn minimum_error(values: &[f32]) -> Option<f32> {
    let bins = Bins::of(values)?;
    let (n, total_s, total_q) = bins.moments();
    let mut best: Option<(f64, usize)> = None;
    let (mut c0, mut s0, mut q0) = (0.0f64, 0.0f64, 0.0f64);
    for (i, &c) in bins.counts.iter().enumerate().take(OTSU_BINS - 1) {
        c0 += c;
        s0 += i as f64 * c;
        q0 += (i * i) as f64 * c;
        let c1 = n - c0;
        if c0 < 2.0 || c1 < 2.0 {
            continue;
        }
        let v0 = q0 / c0 - (s0 / c0).powi(2);
        let (s1, q1) = (total_s - s0, total_q - q0);
        let v1 = q1 / c1 - (s1 / c1).powi(2);
        if v0 <= 1e-9 || v1 <= 1e-9 {
            continue;
        }
        let (p0, p1) = (c0 / n, c1 / n);
        let j = p0 * v0.ln() + p1 * v1.ln() - 2.0 * (p0 * p0.ln() + p1 * p1.ln());
        if best.is_none_or(|(b, _)| j < b) {
            best = Some((j, i));
        }
    }
    best.map(|(_, i)| bins.cut(i))
}

/// The 1D squared distance transform of `f` (0 at targets, a large value elsewhere) by the
/// lower envelope of parabolas (Felzenszwalb & Huttenlocher 2012): exact, linear time.
fn distance_1d(f: &[f64]) -> Vec<f64> {
    let n = f.len();
    let mut d = vec![0.0f64; n];
    let mut v = vec![0usize; n];
    let mut z = vec![0.0f64; n + 1];
    let mut k = 0usize;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    let intersect = |q: usize, p: usize| {
        ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64))
    };
    for q in 1..n {
        let mut s = intersect(q, v[k]);
        while s <= z[k] {
            k -= 1;
            s = intersect(q, v[k]);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, out) in d.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let dq = q as f64 - v[k] as f64;
        *out = dq * dq + f[v[k]];
    }
    d
}

/// Squared Euclidean distance from every pixel to the nearest pixel with `target` set
/// (toroidal: distances wrap; the nearest target then lies within one period, so the lines
/// are transformed three periods long and read in the middle one).
fn squared_distance(target: &[bool], w: u32, h: u32, toroidal: bool) -> Vec<f64> {
    let (w, h) = (w as usize, h as usize);
    let far = ((w * w + h * h) * 16) as f64;
    let copies = if toroidal { 3 } else { 1 };
    let offset = |n: usize| if toroidal { n } else { 0 };
    let mut rows = vec![0.0f64; w * h];
    for y in 0..h {
        let line: Vec<f64> = (0..w * copies)
            .map(|i| if target[y * w + i % w] { 0.0 } else { far })
            .collect();
        let d = distance_1d(&line);
        rows[y * w..][..w].copy_from_slice(&d[offset(w)..][..w]);
    }
    let mut out = vec![0.0f64; w * h];
    for x in 0..w {
        let line: Vec<f64> = (0..h * copies).map(|i| rows[(i % h) * w + x]).collect();
        let d = distance_1d(&line);
        for y in 0..h {
            out[y * w + x] = d[offset(h) + y];
        }
    }
    out
}

/// The feature map of a `w`×`h` image of RGB in 0..=255 (see the module docs), with the
/// channel at `weight_percent` % of the colour's standard deviation at the clamp.
pub fn feature_map(
    rgb: &[[f32; 3]],
    w: u32,
    h: u32,
    toroidal: bool,
    weight_percent: u32,
    mask: FeatureMask,
) -> FeatureMap {
    let side = w.min(h);
    let luma: Vec<f32> = rgb.iter().map(|&c| luminance(c)).collect();
    let local = blur(&luma, w, h, (side as f32 / 16.0).max(1.0), toroidal);
    let split = Split {
        detail: luma.iter().zip(&local).map(|(l, m)| l - m).collect(),
        w,
        h,
        toroidal,
        clamp: (side as f32 / 16.0).max(4.0),
        weight: f64::from(weight_percent) / 100.0,
        colour_deviation: colour_deviation(rgb),
    };
    let thin = || split.map(minimum_error(&split.detail), Threshold::MinimumError);
    match mask {
        FeatureMask::Otsu => return split.map(otsu(&split.detail), Threshold::Otsu),
        FeatureMask::MinimumError => return thin(),
        FeatureMask::Auto => {}
    }
    let otsu_map = split.map(otsu(&split.detail), Threshold::Otsu);
    let thin = thin();
    if connected_share(&thin.mask, w, h) < MIN_CONNECTED_SHARE {
        return otsu_map;
    }
    // Otsu's cut fell inside a speckled body (every pixel within a pixel of a border): a thin,
    // rare structure beside it (faint veins in mottled marble) is what the minimum-error
    // threshold finds, taken where its features reach farther.
    let speckle = otsu_map.reach < 1.0 && thin.reach > otsu_map.reach;
    // Otsu's cut took part of the body with the structure (stone33's joints with its darker
    // stones, 27 % of the pixels): the minimum-error class, a structure's share of the pixels
    // whose distance reaches clearly farther, is the structure itself.
    let body = otsu_map.reach >= 1.0
        && thin.share() >= MIN_STRUCTURE_SHARE
        && thin.spread >= MIN_REACH_GAIN * otsu_map.spread;
    if speckle || body {
        thin
    } else {
        otsu_map
    }
}

/// Standard deviation of the colour, all three channels together.
fn colour_deviation(rgb: &[[f32; 3]]) -> f64 {
    let n = rgb.len() as f64;
    (0..3)
        .map(|c| {
            let mean = rgb.iter().map(|p| f64::from(p[c])).sum::<f64>() / n;
            rgb.iter()
                .map(|p| (f64::from(p[c]) - mean).powi(2))
                .sum::<f64>()
                / n
        })
        .sum::<f64>()
        .sqrt()
}

/// Share of the minimum-error class's pixels that must touch another of its pixels (among
/// their 8 neighbours) for the class to count as a structure: a thin vein's pixels all do,
/// while the tail of a noisy body is scattered (a random 3 % of the pixels has a member among
/// its 8 neighbours about 22 % of the time) yet far apart, so its distance alone would pass
/// for structure.
pub const MIN_CONNECTED_SHARE: f64 = 0.5;

/// Share of the `mask`'s pixels with one of their 8 neighbours (wrapping) in the mask.
fn connected_share(mask: &[bool], w: u32, h: u32) -> f64 {
    let (w, h) = (w as usize, h as usize);
    let (mut members, mut touching) = (0usize, 0usize);
    for y in 0..h {
        for x in 0..w {
            if !mask[y * w + x] {
                continue;
            }
            members += 1;
            let touches = [
                (w - 1, h - 1),
                (0, h - 1),
                (1, h - 1),
                (w - 1, 0),
                (1, 0),
                (w - 1, 1),
                (0, 1),
                (1, 1),
            ]
            .iter()
            .any(|&(dx, dy)| mask[((y + dy) % h) * w + (x + dx) % w]);
            if touches {
                touching += 1;
            }
        }
    }
    touching as f64 / members.max(1) as f64
}

/// What every split of one image's local detail shares: the detail, the image's shape, the
/// weight and the colour's deviation.
struct Split {
    detail: Vec<f32>,
    w: u32,
    h: u32,
    toroidal: bool,
    clamp: f32,
    /// The weight, as a fraction of the colour's deviation.
    weight: f64,
    /// Standard deviation of the colour, all three channels together.
    colour_deviation: f64,
}

impl Split {
    /// The map of the split at `threshold` by `rule` (the smaller class the feature); no
    /// channel when there is no threshold or one class is empty.
    fn map(&self, threshold: Option<f32>, rule: Threshold) -> FeatureMap {
        let n = self.detail.len();
        let none = || FeatureMap {
            mask: vec![false; n],
            channel: vec![0.0; n],
            distance: vec![0.0; n],
            dark: true,
            clamp: self.clamp,
            spread: 0.0,
            reach: 0.0,
            rule,
        };
        let Some(threshold) = threshold else {
            return none();
        };
        let below = self.detail.iter().filter(|&&d| d < threshold).count();
        // The smaller class is the feature; ties go to the dark one.
        let dark = below * 2 <= n;
        let mask: Vec<bool> = self
            .detail
            .iter()
            .map(|&d| if dark { d < threshold } else { d >= threshold })
            .collect();
        if mask.iter().all(|&m| m) || mask.iter().all(|&m| !m) {
            return none();
        }
        let (w, h, clamp) = (self.w, self.h, self.clamp);
        let inverse: Vec<bool> = mask.iter().map(|&m| !m).collect();
        let to_feature = squared_distance(&mask, w, h, self.toroidal);
        let to_background = squared_distance(&inverse, w, h, self.toroidal);
        let signed: Vec<f32> = mask
            .iter()
            .enumerate()
            .map(|(p, &m)| {
                let s = if m {
                    -(to_background[p].sqrt() - 0.5)
                } else {
                    to_feature[p].sqrt() - 0.5
                };
                (s as f32).clamp(-clamp, clamp)
            })
            .collect();
        let count = n as f64;
        let mean = signed.iter().map(|&v| f64::from(v)).sum::<f64>() / count;
        let deviation = (signed
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / count)
            .sqrt();
        let reach = ((deviation - SPECKLE_DEVIATION) / SPECKLE_RAMP).clamp(0.0, 1.0);
        let scale = if deviation > 0.0 {
            self.weight * reach * self.colour_deviation / deviation
        } else {
            0.0
        };
        FeatureMap {
            mask,
            channel: signed
                .iter()
                .map(|&s| (f64::from(s) * scale) as f32)
                .collect(),
            distance: signed,
            dark,
            clamp,
            spread: deviation / f64::from(clamp),
            reach,
            rule,
        }
    }
}

impl FeatureMap {
    /// Whether the channel carries anything (structures found, weight above 0).
    pub fn active(&self) -> bool {
        self.channel.iter().any(|&c| c != 0.0)
    }

    /// Share of the pixels that are feature pixels.
    pub fn share(&self) -> f64 {
        self.mask.iter().filter(|&&m| m).count() as f64 / self.mask.len().max(1) as f64
    }

    /// One line saying what was found in `source`, for the run's report.
    pub fn describe(&self, source: &std::path::Path, weight_percent: u32) -> String {
        format!(
            "feature channel of {}: the {} class{}, {:.1} % of the pixels, distance clamped at {} px, deviation {:.2} px: {}",
            source.display(),
            if self.dark { "dark" } else { "light" },
            match self.rule {
                Threshold::Otsu => "",
                Threshold::MinimumError => " by the minimum-error threshold",
            },
            100.0 * self.share(),
            self.clamp,
            self.spread * f64::from(self.clamp),
            if self.reach <= 0.0 {
                format!("speckle (at most {SPECKLE_DEVIATION} px), channel off")
            } else {
                format!(
                    "weight {:.0} % of the colour's deviation",
                    self.reach * f64::from(weight_percent)
                )
            }
        )
    }

    /// A picture of the map beside its image, for a person to judge what was found: the
    /// mask (features white) and the signed distance (mid grey on the features' border,
    /// darker inside, lighter outside, saturating at the clamp), each `w`×`h`, side by side
    /// with a 4-pixel white gap. Returns the picture's width, height and RGB pixels.
    pub fn picture(&self, rgb: &[[u8; 3]], w: u32, h: u32) -> (u32, u32, Vec<[u8; 3]>) {
        const GAP: u32 = 4;
        let width = 3 * w + 2 * GAP;
        let mut out = vec![[255u8; 3]; (width * h) as usize];
        let peak = self
            .channel
            .iter()
            .fold(0.0f32, |m, &c| m.max(c.abs()))
            .max(f32::MIN_POSITIVE);
        for y in 0..h {
            for x in 0..w {
                let p = (y * w + x) as usize;
                let mask = if self.mask[p] { 255 } else { 0 };
                let distance = (127.5 + 127.5 * self.channel[p] / peak).round() as u8;
                let panels = [rgb[p], [mask; 3], [distance; 3]];
                for (i, colour) in panels.iter().enumerate() {
                    out[(y * width + i as u32 * (w + GAP) + x) as usize] = *colour;
                }
            }
        }
        (width, h, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Asserts that `mask` finds more than `share` of the pixels `truth` marks and that more
    /// than `share` of what it marks is truth.
    fn assert_recalls(mask: &[bool], truth: impl Fn(u32, u32) -> bool, w: u32, h: u32, share: f64) {
        let truths = (0..w * h).filter(|&p| truth(p % w, p / w)).count();
        let found = (0..w * h)
            .filter(|&p| mask[p as usize] && truth(p % w, p / w))
            .count();
        let marked = mask.iter().filter(|&&m| m).count();
        assert!(
            found as f64 > share * truths as f64,
            "{found} of {truths} found"
        );
        assert!(
            found as f64 > share * marked as f64,
            "{found} of {marked} marked"
        );
    }

    fn brute(target: &[bool], w: u32, h: u32, toroidal: bool) -> Vec<f64> {
        let (wi, hi) = (w as i64, h as i64);
        (0..hi * wi)
            .map(|p| {
                let (x, y) = (p % wi, p / wi);
                let mut best = f64::INFINITY;
                for q in 0..hi * wi {
                    if !target[q as usize] {
                        continue;
                    }
                    let (mut dx, mut dy) = ((q % wi - x).abs(), (q / wi - y).abs());
                    if toroidal {
                        dx = dx.min(wi - dx);
                        dy = dy.min(hi - dy);
                    }
                    best = best.min((dx * dx + dy * dy) as f64);
                }
                best
            })
            .collect()
    }

    #[test]
    fn the_distance_transform_is_exact_with_and_without_wrapping() {
        let (w, h) = (23u32, 17u32);
        let mut state = 12345u32;
        let target: Vec<bool> = (0..w * h)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                state >> 28 == 0
            })
            .collect();
        for toroidal in [false, true] {
            assert_eq!(
                squared_distance(&target, w, h, toroidal),
                brute(&target, w, h, toroidal),
                "toroidal {toroidal}"
            );
        }
    }

    /// Dark thin lines on a light ground: the lines are the feature, the distance grows away
    /// from them and is negative on them; inverted, the light lines are found instead.
    #[test]
    fn thin_lines_are_the_feature_whatever_their_polarity() {
        let (w, h) = (64u32, 64u32);
        let image = |line: f32, ground: f32| -> Vec<[f32; 3]> {
            (0..w * h)
                .map(|p| {
                    let (x, y) = (p % w, p / w);
                    let v = if x % 16 == 3 || y % 32 == 9 {
                        line
                    } else {
                        ground
                    };
                    [v, v * 0.9, v * 0.8]
                })
                .collect()
        };
        for (line, ground, dark) in [(40.0, 200.0, true), (220.0, 60.0, false)] {
            let map = feature_map(&image(line, ground), w, h, true, 100, FeatureMask::Auto);
            assert_eq!(map.dark, dark);
            for p in 0..(w * h) as usize {
                let (x, y) = (p as u32 % w, p as u32 / w);
                let on_line = x % 16 == 3 || y % 32 == 9;
                assert_eq!(map.mask[p], on_line, "pixel ({x}, {y})");
                assert_eq!(map.channel[p] < 0.0, on_line, "pixel ({x}, {y})");
            }
            // Farther from the lines, larger (up to the clamp).
            let at = |x: u32, y: u32| map.channel[(y * w + x) as usize];
            assert!(at(4, 20) < at(5, 20) && at(5, 20) < at(7, 20));
            assert_eq!(map.clamp, 4.0);
            assert_eq!(at(11, 20), at(12, 20), "clamped at 4 pixels");
        }
    }

    #[test]
    fn flat_images_and_speckle_get_no_channel_structures_do() {
        let flat = vec![[90.0f32, 90.0, 90.0]; 32 * 32];
        let map = feature_map(&flat, 32, 32, true, 100, FeatureMask::Auto);
        assert!(map.mask.iter().all(|&m| !m));
        assert!(!map.active());
        // Independent pixels: every pixel lies within a pixel or so of a class border.
        let mut state = 7u32;
        let speckle: Vec<[f32; 3]> = (0..64 * 64)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let v = (state >> 24) as f32;
                [v, v, v]
            })
            .collect();
        let map = feature_map(&speckle, 64, 64, true, 100, FeatureMask::Auto);
        assert!(
            map.spread * f64::from(map.clamp) < SPECKLE_DEVIATION,
            "{map:?}"
        );
        assert!(!map.active() && map.reach == 0.0);
        // Dark 4×4 blobs every 16 pixels: the channel is on, at the weight asked for, and at weight 0 off.
        let blobs: Vec<[f32; 3]> = (0..64 * 64u32)
            .map(|p| {
                let (x, y) = (p % 64, p / 64);
                let v = if x % 16 < 4 && y % 16 < 4 {
                    30.0
                } else {
                    180.0
                };
                [v, v, v]
            })
            .collect();
        let map = feature_map(&blobs, 64, 64, true, 100, FeatureMask::Auto);
        assert!(map.active() && map.reach == 1.0, "{map:?}");
        let colour_deviation = {
            let mean = blobs.iter().map(|p| f64::from(p[0])).sum::<f64>() / 4096.0;
            (3.0 * blobs
                .iter()
                .map(|p| (f64::from(p[0]) - mean).powi(2))
                .sum::<f64>()
                / 4096.0)
                .sqrt()
        };
        let channel_mean = map.channel.iter().map(|&c| f64::from(c)).sum::<f64>() / 4096.0;
        let channel_deviation = (map
            .channel
            .iter()
            .map(|&c| (f64::from(c) - channel_mean).powi(2))
            .sum::<f64>()
            / 4096.0)
            .sqrt();
        assert!((channel_deviation / colour_deviation - 1.0).abs() < 1e-3);
        assert!(!feature_map(&blobs, 64, 64, true, 0, FeatureMask::Auto).active());
    }

    /// Faint thin light veins (3 % of the pixels) in a mottled body: Otsu's cut falls inside
    /// the body's mottle (about half the pixels, every one within a pixel or so of a border),
    /// the minimum-error threshold finds the veins; without the veins the body stays speckle.
    #[test]
    fn faint_veins_in_a_mottled_body_are_found_by_the_minimum_error_threshold() {
        let (w, h) = (128u32, 128u32);
        let on_vein = |x: u32, y: u32| x % 50 == 7 || (x + y) % 61 == 5;
        let mut state = 99u32;
        let plain: Vec<[f32; 3]> = (0..w * h)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let v = 150.0 + ((state >> 24) as f32 - 128.0) * 0.2;
                [v, v, v]
            })
            .collect();
        let image: Vec<[f32; 3]> = plain
            .iter()
            .enumerate()
            .map(|(p, &c)| {
                let (x, y) = (p as u32 % w, p as u32 / w);
                let v = c[0] + if on_vein(x, y) { 70.0 } else { 0.0 };
                [v, v, v]
            })
            .collect();
        let map = feature_map(&image, w, h, true, 100, FeatureMask::Auto);
        assert_eq!(
            map.rule,
            Threshold::MinimumError,
            "{}",
            map.describe("veins".as_ref(), 100)
        );
        assert!(!map.dark && map.reach == 1.0);
        let veins = (0..w * h).filter(|&p| on_vein(p % w, p / w)).count();
        assert!((0.02..0.05).contains(&(veins as f64 / (w * h) as f64)));
        // Most vein pixels found, and most of what is marked is vein.
        assert_recalls(&map.mask, on_vein, w, h, 0.8);
        // The body alone: speckle by either threshold, no channel.
        assert!(!feature_map(&plain, w, h, true, 100, FeatureMask::Auto).active());
    }

    /// The reason for the channel: two pixels whose 5×5 colour neighbourhoods are equal but
    /// that lie at different distances from a crack get equal appearance vectors from colour
    /// alone and different ones with the channel.
    #[test]
    fn the_channel_tells_apart_what_the_colour_neighbourhood_cannot() {
        use crate::appearance::shared_appearance;
        let (w, h) = (128u32, 128u32);
        let image: Vec<[f32; 3]> = (0..w * h)
            .map(|p| {
                let (x, y) = (p % w, p / w);
                // A dark crack along x = 10..12 and a little texture far from both pixels.
                let v = if (10..12).contains(&x) {
                    30.0
                } else if x > 100 && (x + y) % 3 == 0 {
                    120.0
                } else {
                    200.0
                };
                [v, v, v]
            })
            .collect();
        let map = feature_map(&image, w, h, true, 100, FeatureMask::Auto);
        assert_eq!(map.clamp, 8.0);
        let (near, far) = ((40 * w + 15) as usize, (40 * w + 50) as usize);
        let (colour_only, _) = shared_appearance(&[&image], None, w, h, 1, true);
        assert_eq!(colour_only[0][near], colour_only[0][far]);
        let (with_feature, _) = shared_appearance(&[&image], Some(&[&map.channel]), w, h, 1, true);
        assert_ne!(with_feature[0][near], with_feature[0][far]);
    }

    /// Thin dark joints (about 8 % of the pixels) between stones with darker 8-pixel spots
    /// (about a quarter of the pixels): Otsu's split takes the spots with the joints (and is
    /// no speckle: it reaches its full weight), the minimum-error class is the joints alone,
    /// connected and reaching farther, so the rule takes it; with the forced masks each split
    /// is the one asked for.
    #[test]
    fn joints_between_mottled_stones_are_found_by_the_minimum_error_threshold() {
        let (w, h) = (96u32, 96u32);
        let on_joint = |x: u32, y: u32| x % 24 == 0 || y % 24 == 0;
        let spot = |x: u32, y: u32| x % 16 >= 4 && x % 16 < 12 && y % 16 >= 4 && y % 16 < 12;
        let mut state = 5u32;
        let image: Vec<[f32; 3]> = (0..w * h)
            .map(|p| {
                let (x, y) = (p % w, p / w);
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let noise = ((state >> 24) as f32 - 128.0) / 128.0;
                let v = if on_joint(x, y) {
                    40.0 + 3.0 * noise
                } else if spot(x, y) {
                    130.0 + 30.0 * noise
                } else {
                    190.0 + 30.0 * noise
                };
                [v, v, v]
            })
            .collect();
        let joints = (0..w * h).filter(|&p| on_joint(p % w, p / w)).count();
        assert!((0.06..0.12).contains(&(joints as f64 / (w * h) as f64)));
        let otsu = feature_map(&image, w, h, true, 100, FeatureMask::Otsu);
        let thin = feature_map(&image, w, h, true, 100, FeatureMask::MinimumError);
        assert_eq!(
            (otsu.rule, thin.rule),
            (Threshold::Otsu, Threshold::MinimumError)
        );
        let shares = |m: &FeatureMap| format!("share {:.3}, spread {:.3}", m.share(), m.spread);
        assert!(
            otsu.share() > 0.15 && otsu.reach == 1.0,
            "Otsu's split takes the spots too and is no speckle: {}; minimum error {}",
            shares(&otsu),
            shares(&thin)
        );
        let auto = feature_map(&image, w, h, true, 100, FeatureMask::Auto);
        assert_eq!(
            auto.rule,
            Threshold::MinimumError,
            "{}; minimum error {}, {} connected",
            auto.describe("joints".as_ref(), 100),
            shares(&thin),
            connected_share(&thin.mask, w, h)
        );
        assert_recalls(&auto.mask, on_joint, w, h, 0.9);
        // Thin lines alone on one ground: Otsu's split is the structure, the rule keeps it.
        let lines: Vec<[f32; 3]> = (0..w * h)
            .map(|p| {
                let v = if on_joint(p % w, p / w) { 40.0 } else { 190.0 };
                [v, v, v]
            })
            .collect();
        assert_eq!(
            feature_map(&lines, w, h, true, 100, FeatureMask::Auto).rule,
            Threshold::Otsu
        );
    }
}
