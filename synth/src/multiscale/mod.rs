//! Multiscale texture synthesis from an exemplar graph (Han, Risser, Ramamoorthi & Grinspun
//! 2008, "Multiscale Texture Synthesis"; Han's thesis ch. 4–5), on the 2D synthesizer's core:
//! Gaussian stacks, quantized appearance vectors, k-coherence, parity subpasses, integer
//! distances and windows of the unbounded plane. See `docs/multiscale.md`.
//!
//! [`ExemplarGraph`] (TOML) → [`analyze_graph`] (superexemplar depth sets, one appearance
//! space per distinct set, coherence sets across exemplars with colour transfers) →
//! [`synthesize_multiscale_cpu`] or the GPU twin, which agree exactly.

mod analysis;
mod atlas;
mod cpu;
pub(crate) mod gpu;
mod graph;
mod superexemplar;

pub use analysis::{
    analyze_graph, analyze_topology, fit_transfer, Candidate, DepthSetAnalysis, ExemplarInfo,
    MemberAnalysis, MultiscaleAnalysis, TRANSFER_ONE,
};
pub use cpu::{
    check_multiscale_window, colour, correct_subpass_multiscale, meta, offset_move,
    plan_multiscale, spacing_of, spans_period_multiscale, synthesize_multiscale_cpu,
    upsample_jitter_multiscale, MultiscaleLevel, MultiscaleParams, MultiscaleSynthesis, PixelState,
    MAGNIFIED, MAX_DEPTH, MAX_OFFSET_MOVE, MAX_TRANSFER,
};
pub use gpu::{CorrectionVariant, MultiscaleGpu};
pub use graph::{
    ExemplarGraph, GraphEdge, GraphError, Topology, MAX_GRAPH_EXEMPLARS, MAX_MULTISCALE_SIDE,
    R_MAX_MARGIN,
};
pub use superexemplar::{StackLevel, Superexemplar};
