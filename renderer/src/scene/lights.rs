//! `[[light]]` and `[environment]`: where the light comes from.

use super::check::ColorKind;
use super::location::{join, Doc};
use super::raw::{RawEnvironment, RawLight, RawLightKind};
use super::{Environment, Light, SceneError};
use std::path::Path;
use toml::Spanned;

/// A quad light whose edges span less than this fraction of `|edge_u|·|edge_v|` is degenerate
/// (parallel edges): it would emit nothing and break area sampling with a zero pdf.
const MIN_QUAD_SINE: f32 = 1e-6;

/// Validates one light table; `label` is its field path prefix (`light #1`).
pub(super) fn light(doc: &Doc, raw: &Spanned<RawLight>, label: &str) -> Result<Light, SceneError> {
    let table = raw.span();
    let raw = raw.get_ref();
    let field = |key: &str| join(label, key);
    let radiance = doc.color(&raw.radiance, &field("radiance"), ColorKind::Unbounded)?;
    match raw.kind.get_ref() {
        RawLightKind::Sphere => {
            let why = "only quad lights have it (sphere lights take center and radius)";
            doc.reject(&raw.corner, label, "corner", why)?;
            doc.reject(&raw.edge_u, label, "edge_u", why)?;
            doc.reject(&raw.edge_v, label, "edge_v", why)?;
            doc.reject(&raw.two_sided, label, "two_sided", why)?;
            let needs = "a sphere light needs center, radius and radiance";
            let center = doc.require(&raw.center, &table, label, "center", needs)?;
            let radius = doc.require(&raw.radius, &table, label, "radius", needs)?;
            Ok(Light::Sphere {
                center: doc.vec3(center, &field("center"))?,
                radius: doc.number(radius, &field("radius"), |r| r > 0.0, "> 0")?,
                radiance,
            })
        }
        RawLightKind::Quad => {
            let why = "only sphere lights have it (quad lights take corner, edge_u and edge_v)";
            doc.reject(&raw.center, label, "center", why)?;
            doc.reject(&raw.radius, label, "radius", why)?;
            let needs = "a quad light needs corner, edge_u, edge_v and radiance";
            let corner = doc.require(&raw.corner, &table, label, "corner", needs)?;
            let edge_u = doc.require(&raw.edge_u, &table, label, "edge_u", needs)?;
            let edge_v = doc.require(&raw.edge_v, &table, label, "edge_v", needs)?;
            let corner = doc.vec3(corner, &field("corner"))?;
            let (u, v) = (
                doc.vec3(edge_u, &field("edge_u"))?,
                doc.vec3(edge_v, &field("edge_v"))?,
            );
            let area = u.cross(v).length();
            if area <= MIN_QUAD_SINE * u.length() * v.length() {
                return Err(doc.invalid(
                    edge_v.span(),
                    field("edge_v"),
                    format!(
                        "the quad has zero area (edge_u {u} and edge_v {v} are parallel or zero)"
                    ),
                ));
            }
            Ok(Light::Quad {
                corner,
                edge_u: u,
                edge_v: v,
                radiance,
                two_sided: raw.two_sided.as_ref().is_some_and(|t| *t.get_ref()),
            })
        }
    }
}

/// Validates `[environment]` (black when absent); a map's path is resolved against `base`
/// and must exist.
pub(super) fn environment(
    doc: &Doc,
    raw: Option<&Spanned<RawEnvironment>>,
    base: &Path,
) -> Result<Environment, SceneError> {
    let Some(raw) = raw else {
        return Ok(Environment::Constant(glam::Vec3::ZERO));
    };
    let table = raw.span();
    let raw = raw.get_ref();
    match (&raw.radiance, &raw.path) {
        (Some(_), Some(p)) => Err(doc.invalid(
            p.span(),
            "environment.path",
            "radiance and path are exclusive: give a constant radiance or a map",
        )),
        (None, None) => Err(doc.invalid(
            table,
            "environment",
            "needs radiance = [r, g, b] or path = \"map.exr\" (or leave the table out for black)",
        )),
        (Some(r), None) => {
            let why = "only a map (path) has it";
            doc.reject(&raw.intensity, "environment", "intensity", why)?;
            doc.reject(&raw.rotation, "environment", "rotation", why)?;
            Ok(Environment::Constant(doc.color(
                r,
                "environment.radiance",
                ColorKind::Unbounded,
            )?))
        }
        (None, Some(p)) => {
            let path = base.join(p.get_ref());
            if path.exists() && !path.is_file() {
                return Err(doc.invalid(
                    p.span(),
                    "environment.path",
                    format!("{} is not a file", path.display()),
                ));
            }
            if !path.exists() {
                return Err(SceneError::MissingFile {
                    file: doc.file.to_path_buf(),
                    line: doc.line(p.span().start),
                    field: "environment.path".into(),
                    missing: path,
                });
            }
            let intensity = match &raw.intensity {
                Some(i) => doc.number(i, "environment.intensity", |v| v > 0.0, "> 0")?,
                None => 1.0,
            };
            let rotation_deg = match &raw.rotation {
                Some(r) => doc.number(r, "environment.rotation", |_| true, "finite")?,
                None => 0.0,
            };
            Ok(Environment::LatLong {
                path,
                intensity,
                rotation_deg,
            })
        }
    }
}
