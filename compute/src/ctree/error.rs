//! Errors of the compressed trees: each names the field or parameter and the limit at fault.

/// Why a compressed tree could not be built or read.
#[derive(Debug, thiserror::Error)]
pub enum CtreeError {
    /// The input field is outside what a tree holds.
    #[error("compressed tree: field {name} {why}")]
    Field {
        /// The field (a file or a generator's name).
        name: String,
        /// What is wrong, with the limit.
        why: String,
    },
    /// A build parameter is out of range.
    #[error("compressed tree: {field} = {value} {why}")]
    Param {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: String,
        /// The limit.
        why: String,
    },
    /// The device failed.
    #[error("compressed tree: device build failed: {0}")]
    Device(String),
}
