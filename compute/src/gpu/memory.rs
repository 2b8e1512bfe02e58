//! How host data reaches buffers: through the mapping when the memory allows it, or through a
//! staging buffer as on a discrete GPU.
//!
//! lavapipe's one heap is host-visible and coherent, so every upload and readback there is a
//! mapped copy and the staging path, the only one a discrete GPU's device-local memory allows,
//! would never run. `LAZYSOLID_MEMORY=device-local` makes the core treat all memory as
//! device-local only, so CI exercises that path (and its barriers) on lavapipe.

use super::error::{GpuError, GpuResult};

/// Environment variable choosing the [`MemoryMode`]: `auto` (the default) or `device-local`.
pub const MEMORY_ENV: &str = "LAZYSOLID_MEMORY";

/// How [`GpuBuffer`](super::GpuBuffer) uploads and reads back host data.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MemoryMode {
    /// Mapped copies where the memory is host-visible and coherent, staging elsewhere.
    #[default]
    Auto,
    /// Every upload and readback through a staging buffer and a transfer, never a mapped write
    /// into or read from a buffer the kernels use: what a discrete GPU's device-local memory
    /// forces, available on any device.
    DeviceLocal,
}

impl MemoryMode {
    /// Every mode, in the order error messages list them.
    pub const ALL: [MemoryMode; 2] = [MemoryMode::Auto, MemoryMode::DeviceLocal];

    /// The word [`MEMORY_ENV`] and `lazysolid device` use.
    pub fn name(self) -> &'static str {
        match self {
            MemoryMode::Auto => "auto",
            MemoryMode::DeviceLocal => "device-local",
        }
    }

    /// Parses a mode's name; `source` names where the text came from in the error.
    ///
    /// # Errors
    /// [`GpuError::BadSetting`] naming `source`, the text and the accepted words.
    pub fn parse(text: &str, source: &str) -> GpuResult<MemoryMode> {
        let trimmed = text.trim();
        Self::ALL
            .into_iter()
            .find(|m| m.name() == trimmed)
            .ok_or_else(|| GpuError::BadSetting {
                setting: source.to_string(),
                value: text.to_string(),
                expected: Self::ALL.map(MemoryMode::name).join(", "),
            })
    }

    /// The mode [`MEMORY_ENV`] asks for: [`MemoryMode::Auto`] when it is unset or empty.
    ///
    /// # Errors
    /// An unknown value (it is never ignored: a misspelt switch would silently test nothing).
    pub fn from_env() -> GpuResult<MemoryMode> {
        match std::env::var(MEMORY_ENV) {
            Ok(v) if !v.trim().is_empty() => Self::parse(&v, MEMORY_ENV),
            Ok(_) | Err(std::env::VarError::NotPresent) => Ok(MemoryMode::Auto),
            Err(std::env::VarError::NotUnicode(v)) => Err(GpuError::BadSetting {
                setting: MEMORY_ENV.to_string(),
                value: v.to_string_lossy().into_owned(),
                expected: Self::ALL.map(MemoryMode::name).join(", "),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_words_are_refused() {
        for m in MemoryMode::ALL {
            assert_eq!(MemoryMode::parse(m.name(), "test").unwrap(), m);
        }
        let err = MemoryMode::parse("devicelocal", MEMORY_ENV).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains(MEMORY_ENV)
                && text.contains("devicelocal")
                && text.contains("auto, device-local"),
            "{text}"
        );
    }
}
