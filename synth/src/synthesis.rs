//! The result of a synthesis: the exemplar coordinates of every computed level, and the
//! colours they stand for.

use super::analysis::ExemplarAnalysis;
use super::coords::unpack;
use super::error::{SynthError, SynthResult};
use super::exemplar::Exemplar;
use super::params::SynthParams;
use super::plan::Region;

/// Largest side of a synthesized window.
pub const MAX_WINDOW_SIDE: u32 = 8192;

/// Largest magnitude of a window origin: absolute positions, their padding and the jitter
/// hash's inputs stay well inside `i32`.
pub const MAX_WINDOW_ORIGIN: i32 = 1 << 28;

/// Coordinates of one level over the region computed there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelCoords {
    /// The computed region (window plus padding, in this level's absolute positions).
    pub region: Region,
    /// Packed exemplar coordinates (see `coords.rs`), row-major over `region`.
    pub coords: Vec<u32>,
}

/// A synthesized window.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Synthesis {
    /// The requested window of the finest level.
    pub window: Region,
    /// Levels `0..=L` (coarsest first); a synthesizer asked not to keep them holds only `L`.
    pub levels: Vec<LevelCoords>,
}

impl Synthesis {
    /// Packed coordinates of the requested window, row-major (the padding cut away).
    pub fn window_coords(&self) -> Vec<u32> {
        let finest = self
            .levels
            .last()
            .expect("a synthesis has its finest level");
        let r = finest.region;
        let (ox, oy) = (
            (self.window.origin[0] - r.origin[0]) as usize,
            (self.window.origin[1] - r.origin[1]) as usize,
        );
        let mut out = Vec::with_capacity(self.window.pixels());
        for y in 0..self.window.size[1] as usize {
            let row = (oy + y) * r.size[0] as usize + ox;
            out.extend_from_slice(&finest.coords[row..row + self.window.size[0] as usize]);
        }
        out
    }

    /// The window's colours: the exemplar looked up at the synthesized coordinates.
    pub fn colours(&self, exemplar: &Exemplar) -> Vec<[u8; 3]> {
        self.window_coords()
            .into_iter()
            .map(|c| {
                let (x, y) = unpack(c);
                exemplar.at(x, y)
            })
            .collect()
    }
}

/// Checks that `window` and `params` fit `analysis`.
///
/// # Errors
/// [`SynthError::Parameter`] naming the window field or parameter and its limit.
pub fn check_window(
    analysis: &ExemplarAnalysis,
    params: &SynthParams,
    window: Region,
) -> SynthResult<()> {
    check_window_bounds(window)?;
    if params.passes.len() != analysis.levels.len() {
        return Err(SynthError::Parameter {
            name: "passes",
            value: format!("{} counts", params.passes.len()),
            limit: format!("the exemplar has {} levels", analysis.levels.len()),
        });
    }
    if params.jitter.len() != analysis.levels.len() {
        return Err(SynthError::Parameter {
            name: "jitter",
            value: format!("{} strengths", params.jitter.len()),
            limit: format!("the exemplar has {} levels", analysis.levels.len()),
        });
    }
    Ok(())
}

/// Checks a window's size and origin against the limits every synthesizer shares (the 2D and
/// the multiscale one).
///
/// # Errors
/// [`SynthError::Parameter`] naming the window's width, height or offset.
pub fn check_window_bounds(window: Region) -> SynthResult<()> {
    for (name, side) in [
        ("window width", window.size[0]),
        ("window height", window.size[1]),
    ] {
        if !(1..=MAX_WINDOW_SIDE).contains(&side) {
            return Err(SynthError::Parameter {
                name,
                value: side.to_string(),
                limit: format!("must lie in 1..={MAX_WINDOW_SIDE}"),
            });
        }
    }
    for o in window.origin {
        if o.unsigned_abs() > MAX_WINDOW_ORIGIN as u32 {
            return Err(SynthError::Parameter {
                name: "window offset",
                value: o.to_string(),
                limit: format!(
                    "each component must lie in -{MAX_WINDOW_ORIGIN}..={MAX_WINDOW_ORIGIN}"
                ),
            });
        }
    }
    Ok(())
}
