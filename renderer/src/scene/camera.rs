//! `[camera]` and `[render]`: the view and the image.

use super::location::Doc;
use super::raw::{RawCamera, RawRender};
use super::{Camera, Lens, RenderSettings, SceneError};
use glam::Vec3;
use toml::Spanned;

/// Largest image side: beyond it a render is a mistake rather than a wish.
pub const MAX_IMAGE_SIDE: u32 = 8192;
/// Largest sample count per pixel (2^20).
pub const MAX_SPP: u32 = 1 << 20;
/// Largest path depth: the most bounces (scattering events) a path may make.
pub const MAX_DEPTH: u32 = 64;
/// Default path depth (bounces).
pub const DEFAULT_MAX_DEPTH: u32 = 8;
/// Default depth from which Russian roulette may end paths.
pub const DEFAULT_RR_DEPTH: u32 = 3;

/// Sine of the smallest angle allowed between `up` and the view direction: below it the
/// camera's horizontal axis is numerically meaningless.
const MIN_UP_SINE: f32 = 1e-3;

/// Validates `[camera]`.
pub(super) fn camera(doc: &Doc, raw: &Spanned<RawCamera>) -> Result<Camera, SceneError> {
    let table = raw.span();
    let raw = raw.get_ref();
    let position = doc.vec3(&raw.position, "camera.position")?;
    let look_at = doc.vec3(&raw.look_at, "camera.look_at")?;
    if position == look_at {
        return Err(doc.invalid(
            raw.look_at.span(),
            "camera.look_at",
            format!("{look_at} equals camera.position: the view direction is undefined"),
        ));
    }
    let (up, up_span, up_what) = match &raw.up {
        Some(u) => (doc.vec3(u, "camera.up")?, u.span(), "camera.up"),
        None => (Vec3::Y, table.clone(), "the default up [0, 1, 0]"),
    };
    let view = (look_at - position).normalize();
    if up.length() == 0.0 || view.cross(up.normalize()).length() < MIN_UP_SINE {
        return Err(doc.invalid(
            up_span,
            "camera.up",
            format!(
                "{up_what} is parallel to the view direction {view} (from position to look_at); \
                 give an up that is not"
            ),
        ));
    }
    let fov_y_deg = doc.number(
        &raw.fov_y,
        "camera.fov_y",
        |v| v > 0.0 && v < 180.0,
        "in (0, 180) degrees",
    )?;
    let lens = match (&raw.aperture_radius, &raw.focus_distance) {
        (None, None) => Lens::Pinhole,
        (Some(a), Some(f)) => Lens::ThinLens {
            aperture_radius: doc.number(a, "camera.aperture_radius", |v| v > 0.0, "> 0")?,
            focus_distance: doc.number(f, "camera.focus_distance", |v| v > 0.0, "> 0")?,
        },
        (Some(a), None) => {
            return Err(doc.invalid(
                a.span(),
                "camera.focus_distance",
                "missing: a thin lens needs both aperture_radius and focus_distance",
            ))
        }
        (None, Some(f)) => {
            return Err(doc.invalid(
                f.span(),
                "camera.aperture_radius",
                "missing: a thin lens needs both aperture_radius and focus_distance",
            ))
        }
    };
    Ok(Camera {
        position,
        look_at,
        up,
        fov_y_deg,
        lens,
    })
}

/// Validates `[render]`.
pub(super) fn render(doc: &Doc, raw: &RawRender) -> Result<RenderSettings, SceneError> {
    let optional = |v: &Option<Spanned<u32>>, field: &str, max: u32, default: u32| match v {
        Some(v) => doc.integer(v, field, 0..=max),
        None => Ok(default),
    };
    let max_depth = match &raw.max_depth {
        Some(v) => doc.integer(v, "render.max_depth", 0..=MAX_DEPTH)?,
        None => DEFAULT_MAX_DEPTH,
    };
    Ok(RenderSettings {
        width: doc.integer(&raw.width, "render.width", 1..=MAX_IMAGE_SIDE)?,
        height: doc.integer(&raw.height, "render.height", 1..=MAX_IMAGE_SIDE)?,
        spp: doc.integer(&raw.spp, "render.spp", 1..=MAX_SPP)?,
        max_depth,
        rr_depth: optional(
            &raw.rr_depth,
            "render.rr_depth",
            MAX_DEPTH,
            DEFAULT_RR_DEPTH,
        )?,
        seed: optional(&raw.seed, "render.seed", u32::MAX, 0)?,
    })
}
