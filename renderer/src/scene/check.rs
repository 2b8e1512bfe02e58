//! Value checks shared by every table: finiteness, ranges, colours, required and inapplicable
//! keys. Each failure becomes a [`SceneError::Invalid`] at the value's line, stating the limit.

use super::location::{join, Doc};
use super::raw::SVec3;
use super::SceneError;
use glam::Vec3;
use std::ops::{Range, RangeInclusive};
use toml::Spanned;

/// Which colours may exceed 1: reflectances may not (energy would be created), radiances and
/// complex indices of refraction may.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum ColorKind {
    /// A reflectance or transmittance: each channel in [0, 1].
    Albedo,
    /// A radiance or an optical constant: each channel ≥ 0.
    Unbounded,
}

impl Doc<'_> {
    /// A finite number accepted by `ok`; `limit` says which ones, e.g. `in (0, 180)`.
    pub fn number(
        &self,
        value: &Spanned<f32>,
        field: &str,
        ok: impl Fn(f32) -> bool,
        limit: &str,
    ) -> Result<f32, SceneError> {
        let v = *value.get_ref();
        if !v.is_finite() {
            return Err(self.invalid(value.span(), field, format!("{v} is not finite")));
        }
        if !ok(v) {
            return Err(self.invalid(
                value.span(),
                field,
                format!("{v} is out of range (must be {limit})"),
            ));
        }
        Ok(v)
    }

    /// An integer within `range`.
    pub fn integer(
        &self,
        value: &Spanned<u32>,
        field: &str,
        range: RangeInclusive<u32>,
    ) -> Result<u32, SceneError> {
        let v = *value.get_ref();
        if !range.contains(&v) {
            return Err(self.invalid(
                value.span(),
                field,
                format!(
                    "{v} is out of range (must be in {}..={})",
                    range.start(),
                    range.end()
                ),
            ));
        }
        Ok(v)
    }

    /// A point or direction with finite coordinates.
    pub fn vec3(&self, value: &SVec3, field: &str) -> Result<Vec3, SceneError> {
        let v = Vec3::from_array(*value.get_ref());
        if !v.is_finite() {
            return Err(self.invalid(
                value.span(),
                field,
                format!("{:?} has a non-finite component", value.get_ref()),
            ));
        }
        Ok(v)
    }

    /// An RGB colour: finite, non-negative, and at most 1 per channel for an albedo.
    pub fn color(&self, value: &SVec3, field: &str, kind: ColorKind) -> Result<Vec3, SceneError> {
        let v = self.vec3(value, field)?;
        let max = match kind {
            ColorKind::Albedo => 1.0,
            ColorKind::Unbounded => f32::INFINITY,
        };
        if let Some((i, c)) = v
            .to_array()
            .into_iter()
            .enumerate()
            .find(|&(_, c)| !(0.0..=max).contains(&c))
        {
            let limit = match kind {
                ColorKind::Albedo => "in [0, 1]: a reflectance cannot create energy",
                ColorKind::Unbounded => "≥ 0",
            };
            return Err(self.invalid(
                value.span(),
                field,
                format!(
                    "channel {i} of {:?} is {c}, out of range (must be {limit})",
                    value.get_ref()
                ),
            ));
        }
        Ok(v)
    }

    /// A key that the table must have in its current form (`why` says which form).
    pub fn require<'v, T>(
        &self,
        value: &'v Option<Spanned<T>>,
        table: &Range<usize>,
        table_label: &str,
        key: &str,
        why: &str,
    ) -> Result<&'v Spanned<T>, SceneError> {
        value.as_ref().ok_or_else(|| {
            self.invalid(
                table.clone(),
                join(table_label, key),
                format!("missing ({why})"),
            )
        })
    }

    /// A key that the table must not have in its current form; `why` names the forms that
    /// accept it.
    pub fn reject<T>(
        &self,
        value: &Option<Spanned<T>>,
        table_label: &str,
        key: &str,
        why: &str,
    ) -> Result<(), SceneError> {
        match value {
            Some(v) => Err(self.invalid(v.span(), join(table_label, key), why.to_string())),
            None => Ok(()),
        }
    }
}
