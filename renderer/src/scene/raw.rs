//! The scene file as serde reads it: one struct per TOML table, every value wrapped in
//! [`Spanned`] so that validation can point at the line it came from. Nothing here is checked
//! beyond TOML types and key names (`deny_unknown_fields`); `resolve` does the rest.

use serde::Deserialize;
use toml::Spanned;

/// Three numbers (a point, a direction or an RGB colour) with their place in the file.
pub(super) type SVec3 = Spanned<[f32; 3]>;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub camera: Spanned<RawCamera>,
    pub render: Spanned<RawRender>,
    #[serde(default)]
    pub mesh: Vec<Spanned<RawMesh>>,
    #[serde(default)]
    pub material: Vec<Spanned<RawMaterial>>,
    #[serde(default)]
    pub instance: Vec<Spanned<RawInstance>>,
    #[serde(default)]
    pub light: Vec<Spanned<RawLight>>,
    pub environment: Option<Spanned<RawEnvironment>>,
    #[serde(default)]
    pub cut: Vec<Spanned<RawCut>>,
    #[serde(default)]
    pub fracture: Vec<Spanned<RawFracture>>,
    pub explosion: Option<Spanned<RawExplosion>>,
    pub animation: Option<Spanned<RawAnimation>>,
}

/// `[camera]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCamera {
    pub position: SVec3,
    pub look_at: SVec3,
    pub up: Option<SVec3>,
    pub fov_y: Spanned<f32>,
    pub aperture_radius: Option<Spanned<f32>>,
    pub focus_distance: Option<Spanned<f32>>,
}

/// `[render]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRender {
    pub width: Spanned<u32>,
    pub height: Spanned<u32>,
    pub spp: Spanned<u32>,
    pub max_depth: Option<Spanned<u32>>,
    pub rr_depth: Option<Spanned<u32>>,
    pub seed: Option<Spanned<u32>>,
}

/// Built-in generated meshes.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawShape {
    Quad,
    Cube,
    Sphere,
}

/// `[[mesh]]`: a file or a built-in shape.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMesh {
    pub name: Spanned<String>,
    pub path: Option<Spanned<String>>,
    pub shape: Option<Spanned<RawShape>>,
    pub subdivisions: Option<Spanned<u32>>,
    pub normalize: Option<Spanned<bool>>,
}

/// Material kinds as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawMaterialKind {
    Lambertian,
    Conductor,
    Plastic,
    Dielectric,
    Emissive,
    Glint,
}

/// Blending modes of a glint microstructure as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawGlintBlend {
    None,
    Linear,
    Variance,
    Histogram,
}

/// How a glint material finds its surface coordinates, as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawGlintUv {
    Planar,
    Spherical,
    Mesh,
}

/// How a normal map is filtered over a footprint, as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawNormalFilter {
    None,
    Mip,
    Vmf,
}

/// How a glint material evaluates its P-NDF, as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawGlintEvaluation {
    Pruned,
    Explicit,
}

/// Measured metals a conductor may name instead of giving η and κ.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawPreset {
    Gold,
    Silver,
    Copper,
    Aluminium,
}

/// `[[material]]`: one flat table for every kind, so that a key another kind accepts gets a
/// message naming that kind instead of serde's generic "unknown field".
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    pub name: Spanned<String>,
    pub kind: Spanned<RawMaterialKind>,
    pub color: Option<SVec3>,
    pub k: Option<SVec3>,
    pub emission: Option<SVec3>,
    pub roughness: Option<Spanned<f32>>,
    pub ior: Option<Spanned<f32>>,
    pub preset: Option<Spanned<RawPreset>>,
    pub texture: Option<Spanned<RawTexture>>,
    pub albedo_map: Option<Spanned<String>>,
    pub albedo_ctree_step: Option<Spanned<f32>>,
    pub normal_filter: Option<Spanned<RawNormalFilter>>,
    pub vmf_lobes: Option<Spanned<u32>>,
    pub normal_map: Option<Spanned<String>>,
    pub height_map: Option<Spanned<String>>,
    pub height_scale: Option<Spanned<f32>>,
    pub intrinsic_roughness: Option<Spanned<f32>>,
    pub scale: Option<Spanned<f32>>,
    pub blend: Option<Spanned<RawGlintBlend>>,
    pub patch: Option<Spanned<u32>>,
    pub seed: Option<Spanned<u32>>,
    pub uv: Option<Spanned<RawGlintUv>>,
    pub evaluation: Option<Spanned<RawGlintEvaluation>>,
}

/// Solid texture kinds as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawTextureKind {
    Marble,
    Wood,
    Checker,
    Volume,
    Synthesized,
}

/// `texture = { … }` of a material.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTexture {
    pub kind: Spanned<RawTextureKind>,
    pub color_a: Option<SVec3>,
    pub color_b: Option<SVec3>,
    pub scale: Option<Spanned<f32>>,
    pub path: Option<Spanned<String>>,
    pub exemplar: Option<Spanned<String>>,
    pub seed: Option<Spanned<u32>>,
    pub memory: Option<Spanned<String>>,
    /// A [`StoreKind`](crate::scene::StoreKind) by its name, checked when resolved.
    pub store: Option<Spanned<String>>,
    pub resolution: Option<Spanned<u32>>,
    pub filter: Option<Spanned<RawStoreFilter>>,
    pub relief: Option<Spanned<f32>>,
}

/// Store filters as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawStoreFilter {
    Nearest,
    Trilinear,
}

/// `[[instance]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawInstance {
    pub name: Option<Spanned<String>>,
    pub mesh: Spanned<String>,
    pub material: Spanned<String>,
    pub translate: Option<SVec3>,
    pub rotate: Option<SVec3>,
    pub scale: Option<Spanned<f32>>,
}

/// Light kinds as spelled in the file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawLightKind {
    Sphere,
    Quad,
}

/// `[[light]]`: flat like materials, for the same reason.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLight {
    pub kind: Spanned<RawLightKind>,
    pub radiance: SVec3,
    pub center: Option<SVec3>,
    pub radius: Option<Spanned<f32>>,
    pub corner: Option<SVec3>,
    pub edge_u: Option<SVec3>,
    pub edge_v: Option<SVec3>,
    pub two_sided: Option<Spanned<bool>>,
}

/// `[environment]`: a constant radiance or an EXR map.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawEnvironment {
    pub radiance: Option<SVec3>,
    pub path: Option<Spanned<String>>,
    pub intensity: Option<Spanned<f32>>,
    pub rotation: Option<Spanned<f32>>,
}

/// `[[cut]]`: a plane through a named instance, in its mesh's coordinates.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCut {
    pub instance: Spanned<String>,
    pub point: SVec3,
    pub normal: SVec3,
}

/// `[[fracture]]`: Voronoi pieces of a named instance.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFracture {
    pub instance: Spanned<String>,
    pub pieces: Option<Spanned<u32>>,
    pub seed: Option<Spanned<u32>>,
    pub sites: Option<Spanned<Vec<[f32; 3]>>>,
}

/// `[explosion]`: how the pieces fly apart.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawExplosion {
    pub centre: Option<SVec3>,
    pub speed: Spanned<f32>,
    pub spin: Option<Spanned<f32>>,
    pub gravity: Option<SVec3>,
    pub start: Option<Spanned<f32>>,
    pub ground: Option<Spanned<f32>>,
}

/// `[animation]`: frames and their rate.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAnimation {
    pub frames: Spanned<u32>,
    pub fps: Spanned<f32>,
    pub width: Option<Spanned<u32>>,
    pub height: Option<Spanned<u32>>,
    pub spp: Option<Spanned<u32>>,
}
