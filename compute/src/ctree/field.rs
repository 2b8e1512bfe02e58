//! The fields a compressed tree holds: a scalar per sample of a 2D image or a 3D volume, in
//! grey levels (an 8-bit channel spans 0–255), held by the tree in fixed point.

use super::error::CtreeError;
use super::lattice::{Lattice, MAX_LEVELS_2D, MAX_LEVELS_3D};
use super::tree::Border;

pub use crate::shader_constants::CTREE_VALUE_FRAC_BITS as VALUE_FRAC_BITS;
/// Largest magnitude of a value, in grey levels: the forest's pyramid stores values as i16.
pub const MAX_ABS_VALUE: f32 = 511.0;

/// A scalar field sampled on a regular grid of `size` samples (x fastest).
#[derive(Clone, Debug, PartialEq)]
pub struct ScalarField {
    /// 2 or 3.
    pub dims: u32,
    /// Samples per axis (the third is 1 in 2D).
    pub size: [u32; 3],
    /// `size[0]·size[1]·size[2]` values in grey levels.
    pub values: Vec<f32>,
}

impl ScalarField {
    /// A field, checked: 2 or 3 dimensions, values in range and finite, at most the lattice
    /// limits (8,193² or 513³ samples).
    pub fn new(
        name: &str,
        dims: u32,
        size: [u32; 3],
        values: Vec<f32>,
    ) -> Result<ScalarField, CtreeError> {
        let bad = |why: String| CtreeError::Field {
            name: name.to_string(),
            why,
        };
        if dims != 2 && dims != 3 {
            return Err(bad(format!("has {dims} dimensions; a tree holds 2 or 3")));
        }
        let size = if dims == 2 {
            [size[0], size[1], 1]
        } else {
            size
        };
        if size.contains(&0) {
            return Err(bad(format!("has an empty axis (size {size:?})")));
        }
        let expect = size.iter().map(|&s| s as usize).product::<usize>();
        if values.len() != expect {
            return Err(bad(format!(
                "has {} values for a {size:?} grid of {expect}",
                values.len()
            )));
        }
        let lattice = Lattice::fitting(dims, size);
        let limit = if dims == 2 {
            MAX_LEVELS_2D
        } else {
            MAX_LEVELS_3D
        };
        if lattice.n > limit {
            let most = (1u32 << limit) + 1;
            return Err(bad(format!(
                "is {size:?} samples; a {dims}D tree holds at most {most} per axis"
            )));
        }
        if let Some((i, v)) = values
            .iter()
            .enumerate()
            .find(|(_, v)| !v.is_finite() || v.abs() > MAX_ABS_VALUE)
        {
            return Err(bad(format!(
                "sample {i} is {v}; values must be finite and within ±{MAX_ABS_VALUE} grey levels"
            )));
        }
        Ok(ScalarField { dims, size, values })
    }

    /// The lattice the field is compressed on.
    pub fn lattice(&self) -> Lattice {
        Lattice::fitting(self.dims, self.size)
    }

    /// Samples in all.
    pub fn samples(&self) -> usize {
        self.values.len()
    }

    /// Whether the node at finest-lattice position `p` of a level with node `spacing` codes a
    /// residual: a sample, or with [`Border::Anchored`] the first node past a border (a corner
    /// of a cell that holds samples, whose value anchors their predictions).
    pub fn codes(&self, p: [u32; 3], spacing: u32, border: Border) -> bool {
        let past = match border {
            Border::Anchored => spacing,
            Border::Free => 0,
        };
        (0..3).all(|k| p[k] < self.size[k] + past)
    }

    /// The fixed-point value at finest-lattice position `p`, the field's border repeated
    /// beyond its size.
    pub fn fixed_at(&self, p: [u32; 3]) -> i32 {
        let x = p[0].min(self.size[0] - 1) as usize;
        let y = p[1].min(self.size[1] - 1) as usize;
        let z = p[2].min(self.size[2] - 1) as usize;
        let i = x + self.size[0] as usize * (y + self.size[1] as usize * z);
        to_fixed(self.values[i])
    }
}

/// Grey levels to the tree's fixed point (rounded to nearest).
pub fn to_fixed(v: f32) -> i32 {
    (v * (1 << VALUE_FRAC_BITS) as f32).round() as i32
}

/// The tree's fixed point to grey levels.
pub fn from_fixed(v: i32) -> f32 {
    v as f32 / (1 << VALUE_FRAC_BITS) as f32
}
