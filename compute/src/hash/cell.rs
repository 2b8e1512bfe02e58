//! The cell layout of the Robin Hood tables; must match `glsl/include/hash/cells.glsl`.
//!
//! `[ age : 4 | payload : W − 4 − K | key + 1 : K ]` in a W-bit word (W = 64, or 32 for the
//! compact form), K = the universe's [`key_bits`](super::Universe::key_bits). 0 is the empty
//! cell. The age leads so that `atomicMax` decides Robin Hood evictions; after a build the age
//! bits of cell p hold MAT[p].

use super::error::HashError;
use super::keys::Universe;
use crate::shader_constants::HASH_NOT_FOUND;

/// Width of a Robin Hood cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellWidth {
    /// 64-bit cells: key, payload and age for any universe up to 2^58 keys.
    Bits64,
    /// 32-bit cells, where key, payload and age fit (small universes and payloads).
    Bits32,
}

impl CellWidth {
    /// Bits per cell.
    pub fn bits(self) -> u32 {
        match self {
            CellWidth::Bits64 => 64,
            CellWidth::Bits32 => 32,
        }
    }
}

/// A concrete cell layout for one universe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellFormat {
    /// Cell width.
    pub width: CellWidth,
    /// Bits of key + 1.
    pub key_bits: u32,
    /// Bits left for the payload.
    pub payload_bits: u32,
}

impl CellFormat {
    /// The layout of `width`-bit cells for `universe`.
    pub fn new(width: CellWidth, universe: &Universe) -> Result<CellFormat, HashError> {
        let key_bits = universe.key_bits();
        let available = width.bits() as i64 - 4 - key_bits as i64;
        if available < 1 {
            return Err(HashError::UniverseTooLarge {
                universe: universe.describe(),
                key_bits,
                cell_bits: width.bits(),
            });
        }
        Ok(CellFormat {
            width,
            key_bits,
            payload_bits: available.min(32) as u32,
        })
    }

    /// Position of the age bits.
    pub fn age_shift(&self) -> u32 {
        self.width.bits() - 4
    }

    /// Largest storable payload (also below [`HASH_NOT_FOUND`], the "absent" answer).
    pub fn max_payload(&self) -> u32 {
        if self.payload_bits >= 32 {
            HASH_NOT_FOUND - 1
        } else {
            ((1u64 << self.payload_bits) - 1) as u32
        }
    }

    /// Packs an entry (widened to 64 bits for the compact form).
    pub fn pack(&self, age: u32, key: u64, payload: u32) -> u64 {
        ((age as u64) << self.age_shift()) | ((payload as u64) << self.key_bits) | (key + 1)
    }

    /// The age bits.
    pub fn age(&self, cell: u64) -> u32 {
        (cell >> self.age_shift()) as u32
    }

    /// key + 1, or 0 when empty.
    pub fn key1(&self, cell: u64) -> u64 {
        cell & ((1u64 << self.key_bits) - 1)
    }

    /// The payload bits.
    pub fn payload(&self, cell: u64) -> u32 {
        ((cell & ((1u64 << self.age_shift()) - 1)) >> self.key_bits) as u32
    }

    /// The cell with its age bits replaced.
    pub fn with_age(&self, cell: u64, age: u32) -> u64 {
        (cell & ((1u64 << self.age_shift()) - 1)) | ((age as u64) << self.age_shift())
    }

    /// E.g. `64-bit cells (key 27 bits, payload 33 bits)`.
    pub fn describe(&self) -> String {
        format!(
            "{}-bit cells (key {} bits, payload {} bits)",
            self.width.bits(),
            self.key_bits,
            self.payload_bits
        )
    }
}
