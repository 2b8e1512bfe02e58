//! Errors of building a glint microstructure: each names the source (a file or "example"),
//! the field and its limit.

/// Why an example normal map, its tables or a query could not be built.
#[derive(Debug, thiserror::Error)]
pub enum GlintError {
    /// The example is not a square whose edge is a power of two in the supported range, or
    /// its texel count does not match its edge.
    #[error("{source_name}: example is {width}x{height} texels ({texels} given); it must be square with a power-of-two edge from {min} to {max}")]
    Size {
        /// The file or description of the example.
        source_name: String,
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
        /// Texels given.
        texels: usize,
        /// Smallest edge.
        min: usize,
        /// Largest edge.
        max: usize,
    },
    /// A texel's normal is not finite or leaves the unit disc (|(n_x, n_y)| > 1).
    #[error("{source_name}: texel (column {x}, row {y}) has normal ({nx}, {ny}); n_x and n_y must be finite with n_x² + n_y² <= 1")]
    Texel {
        /// The file or description of the example.
        source_name: String,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// x component.
        nx: f32,
        /// y component.
        ny: f32,
    },
    /// A height is not finite.
    #[error("{source_name}: height at (column {x}, row {y}) is {value}; heights must be finite")]
    Height {
        /// The file or description of the height map.
        source_name: String,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The value.
        value: f32,
    },
    /// The target patch edge is not a power of two that fits the example.
    #[error("target patch edge {patch} for a {size}² example; it must be a power of two from 2 to {max} (a quarter of the example edge)")]
    Patch {
        /// Requested target patch edge in texels.
        patch: u32,
        /// Example edge.
        size: u32,
        /// Largest target patch edge.
        max: u32,
    },
    /// A range query square is not a power of two, leaves its target patch or the table.
    #[error("range query square at ({x}, {y}) with edge {edge}: {problem}")]
    Square {
        /// Left column of the square (target texels).
        x: i64,
        /// Bottom row of the square.
        y: i64,
        /// Edge in texels.
        edge: u32,
        /// What is wrong.
        problem: String,
    },
}
