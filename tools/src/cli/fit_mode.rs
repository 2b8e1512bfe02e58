//! `--fit`: how an image becomes a solid exemplar, for every subcommand that synthesizes
//! solids from images (the rules are in `lazysolid_synth` `fit.rs`).

use clap::ValueEnum;
use lazysolid_synth::FitMode;

/// How a solid exemplar is made square with a power-of-two side.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Fit {
    /// Cut the centre square of the largest power of two when that loses at most a quarter of
    /// the side, else resample to the nearest power of two.
    #[default]
    Auto,
    /// Always cut the centre square of the largest power of two that fits.
    Crop,
    /// Always resample the centre square (Lanczos3) to the nearest power of two.
    Resample,
}

impl From<Fit> for FitMode {
    fn from(f: Fit) -> FitMode {
        match f {
            Fit::Auto => FitMode::Auto,
            Fit::Crop => FitMode::Crop,
            Fit::Resample => FitMode::Resample,
        }
    }
}
