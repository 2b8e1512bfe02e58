//! η and κ of a conductor (and of a glint material, a conductor with a microstructure): a
//! measured metal preset or both colours. Separate because the presets are data of their own
//! and two kinds read them.

use crate::scene::check::ColorKind;
use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawMaterial, RawPreset};
use crate::scene::SceneError;
use glam::Vec3;
use std::ops::Range;

/// Complex index of refraction (η, κ) at the red, green and blue wavelengths of the common
/// sRGB reductions of measured spectral data, so that scenes get real metals by name.
pub(super) fn preset_eta_k(preset: RawPreset) -> (Vec3, Vec3) {
    match preset {
        RawPreset::Gold => (
            Vec3::new(0.143_119, 0.374_957, 1.442_48),
            Vec3::new(3.983_16, 2.385_72, 1.603_22),
        ),
        RawPreset::Silver => (
            Vec3::new(0.155_265, 0.116_723, 0.138_342),
            Vec3::new(4.828_35, 3.122_25, 2.146_96),
        ),
        RawPreset::Copper => (
            Vec3::new(0.200_438, 0.924_033, 1.102_21),
            Vec3::new(3.912_95, 2.452_85, 2.142_19),
        ),
        RawPreset::Aluminium => (
            Vec3::new(1.657_46, 0.880_369, 0.521_229),
            Vec3::new(9.223_87, 6.269_52, 4.837),
        ),
    }
}

/// η and κ of a conductor: a preset or both colours, not a mix.
pub(super) fn eta_k(
    doc: &Doc,
    raw: &RawMaterial,
    table: &Range<usize>,
    label: &str,
) -> Result<(Vec3, Vec3), SceneError> {
    if let Some(preset) = &raw.preset {
        let why = "a preset gives both η and κ; give either preset or color and k";
        doc.reject(&raw.color, label, "color", why)?;
        doc.reject(&raw.k, label, "k", why)?;
        return Ok(preset_eta_k(*preset.get_ref()));
    }
    let why = "a conductor needs preset, or color (η) and k (κ)";
    let eta = doc.require(&raw.color, table, label, "color", why)?;
    let k = doc.require(&raw.k, table, label, "k", why)?;
    Ok((
        doc.color(eta, &join(label, "color"), ColorKind::Unbounded)?,
        doc.color(k, &join(label, "k"), ColorKind::Unbounded)?,
    ))
}
