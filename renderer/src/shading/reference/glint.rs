//! The glint material (twin of `render/glint_bsdf.glsl`): a conductor whose NDF is the P-NDF
//! of a microstructure by example over the ray's footprint, with a Smith GGX shadowing term of
//! the example's RMS slope. Written from the GLSL, in f32, so that tests can compare the kernel
//! input by input and check its sampling on the CPU.
//!
//! In the glint frame (x, y: the surface coordinates' directions, z: the shading normal), with
//! s = (h_x, h_y):
//!
//! ```text
//! f cos θ_i = F(wo·h) G2(wo, wi) D_P(s) / (4 wo.z)
//! ```
//!
//! D_P is a density of s, the projected-area measure of h, so it needs no cosine. Sampling
//! draws s from the 4 texels around the footprint centre and reflects wo about h; its
//! solid-angle density is p_s(s) h.z / (4 wo·h).
//!
//! D_P and the sampler are not re-derived here: they are [`ByExampleMap::pndf`] (pruned),
//! [`MaterializedMap::pndf`] (explicit) and [`SampleTexels`], themselves tested against
//! `glint/pndf.glsl`; only what `glint_bsdf.glsl` adds on top (footprint, frame, Fresnel,
//! shadowing, the change of measure) is written out, so a disagreement points at that layer.

use super::bsdf::BsdfSample;
use super::fresnel::fresnel_conductor;
use super::microfacet::ggx_g2;
use super::sampling::make_frame;
use crate::glint::{ByExampleMap, Footprint, MaterializedMap, RangeTable, SampleTexels};
use crate::shading::GpuMaterial;
use glam::{Vec2, Vec3};

/// The fields of the GLSL `GlintRecord` that the shading reads (the map and range table are
/// passed alongside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlintParams {
    /// Intrinsic roughness σ_r.
    pub sigma_r: f32,
    /// Example texels per scene unit.
    pub texels_per_unit: f32,
    /// The spherical projection (`GLINT_UV_SPHERICAL`) rather than the planar one.
    pub spherical: bool,
    /// Pruned traversal (true) or every texel of the footprint (the explicit reference).
    pub prune: bool,
    /// GGX α of the shadowing term.
    pub shadow_alpha: f32,
    /// Largest σ_P in texels.
    pub max_footprint: f32,
}

/// Where a ray meets a glint surface (`GlintShade` and the frame `glint_shade` writes out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlintShade {
    /// Footprint centre (texels).
    pub u: Vec2,
    /// Footprint width σ_P (texels).
    pub sigma_p: f32,
    /// The glint frame's x axis (world): ∂p/∂u made tangent.
    pub t: Vec3,
    /// Its y axis, ns × t.
    pub b: Vec3,
}

impl GlintShade {
    /// The footprint the P-NDF is evaluated over.
    pub fn footprint(&self) -> Footprint {
        // The projections' pixel cone is isotropic (a mesh's texture coordinates, which give
        // the device a stretched footprint, have no CPU twin here).
        Footprint::isotropic(self.u, self.sigma_p)
    }
}

/// The footprint and glint frame at a hit. `p` is the object-space hit point, `scale` the
/// instance's scale, `footprint` the ray cone's width at the hit (scene units), `ns` the world
/// shading normal, `wo_world` the direction back along the ray, `dpdu_x`, `dpdu_z` the object
/// x and z axes in world (unit length). σ_P = ½ width / √cos θ_o (cos θ_o clamped at 0.05: the
/// footprint's stretch at grazing angles, bounded) in texels, clamped to [0.5, max_footprint].
#[allow(clippy::too_many_arguments)]
pub fn glint_shade(
    g: &GlintParams,
    p: Vec3,
    scale: f32,
    footprint: f32,
    ns: Vec3,
    wo_world: Vec3,
    dpdu_x: Vec3,
    dpdu_z: Vec3,
) -> GlintShade {
    let (uv, dpdu) = if g.spherical {
        let d = p - Vec3::splat(0.5);
        let r = d.length().max(1e-6);
        let phi = d.z.atan2(d.x);
        let theta = (d.y / r).clamp(-1.0, 1.0).acos();
        // d/dφ in world: −sin φ x + cos φ z.
        (
            Vec2::new(phi, theta) * r,
            -phi.sin() * dpdu_x + phi.cos() * dpdu_z,
        )
    } else {
        (Vec2::new(p.x, p.z), dpdu_x)
    };
    let t = dpdu - ns * ns.dot(dpdu);
    let tl = t.length();
    let (t, b) = if tl < 1e-6 {
        make_frame(ns)
    } else {
        let t = t / tl;
        (t, ns.cross(t))
    };
    let cos_o = wo_world.dot(ns).abs().max(0.05);
    GlintShade {
        u: uv * (scale * g.texels_per_unit),
        sigma_p: (0.5 * footprint / cos_o.sqrt() * g.texels_per_unit).clamp(0.5, g.max_footprint),
        t,
        b,
    }
}

/// D_P(s) over the shade's footprint, pruned or explicit as the record says.
pub fn glint_pndf(
    g: &GlintParams,
    map: &ByExampleMap,
    table: &RangeTable,
    gs: &GlintShade,
    s: Vec2,
) -> f32 {
    let fp = gs.footprint();
    if g.prune {
        map.pndf(table, &fp, s, g.sigma_r).0
    } else {
        MaterializedMap::covering(map, &fp).pndf(&fp, s, g.sigma_r)
    }
}

fn side(wo: Vec3) -> Vec3 {
    Vec3::new(1.0, 1.0, if wo.z < 0.0 { -1.0 } else { 1.0 })
}

fn eval_local(
    g: &GlintParams,
    map: &ByExampleMap,
    table: &RangeTable,
    m: &GpuMaterial,
    gs: &GlintShade,
    wo: Vec3,
    wi: Vec3,
) -> Vec3 {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (wo + wi).normalize();
    let d = glint_pndf(g, map, table, gs, Vec2::new(h.x, h.y));
    let f = fresnel_conductor(wo.dot(h), Vec3::from(m.color), Vec3::from(m.k));
    f * (d * ggx_g2(wo, wi, g.shadow_alpha) / (4.0 * wo.z))
}

/// f(wo, wi) |cos θ_i| in the glint frame (two-sided, like the conductor: the frame is
/// mirrored when wo.z < 0).
pub fn glint_eval(
    g: &GlintParams,
    map: &ByExampleMap,
    table: &RangeTable,
    m: &GpuMaterial,
    gs: &GlintShade,
    wo: Vec3,
    wi: Vec3,
) -> Vec3 {
    let f = side(wo);
    eval_local(g, map, table, m, gs, wo * f, wi * f)
}

/// Solid-angle density of [`glint_sample`]: the texel mixture's density of s times the
/// Jacobian h.z / (4 wo·h) of s → h → wi. It is not D_P (MIS needs the sampler's own density).
pub fn glint_pdf(g: &GlintParams, map: &ByExampleMap, gs: &GlintShade, wo: Vec3, wi: Vec3) -> f32 {
    let f = side(wo);
    let (wo, wi) = (wo * f, wi * f);
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    let h = (wo + wi).normalize();
    let c = wo.dot(h);
    if c <= 0.0 {
        return 0.0;
    }
    let t = SampleTexels::new(map, gs.u, g.sigma_r);
    t.pdf(Vec2::new(h.x, h.y)) * h.z / (4.0 * c)
}

/// Draws wi with `u` in [0, 1)³: s from the texels around the footprint centre, h = (s, √(1 −
/// |s|²)), wi the reflection of wo; `None` where the GLSL returns false (|s| ≥ 1, h facing away
/// from wo, wi below the surface, zero density).
#[allow(clippy::too_many_arguments)]
pub fn glint_sample(
    g: &GlintParams,
    map: &ByExampleMap,
    table: &RangeTable,
    m: &GpuMaterial,
    gs: &GlintShade,
    wo: Vec3,
    u: Vec3,
) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    let f = side(wo);
    let wo = wo * f;
    let t = SampleTexels::new(map, gs.u, g.sigma_r);
    let s = t.sample(u);
    let r2 = s.length_squared();
    if r2 >= 1.0 {
        return None;
    }
    let h = Vec3::new(s.x, s.y, (1.0 - r2).sqrt());
    let c = wo.dot(h);
    if c <= 0.0 {
        return None;
    }
    let wi = 2.0 * c * h - wo;
    if wi.z <= 0.0 {
        return None;
    }
    let pdf = t.pdf(s) * h.z / (4.0 * c);
    // The GLSL's !(pdf > 0): a NaN density fails too.
    if pdf.is_nan() || pdf <= 0.0 {
        return None;
    }
    Some(BsdfSample {
        wi: wi * f,
        weight: eval_local(g, map, table, m, gs, wo, wi) / pdf,
        pdf,
        specular: false,
    })
}
