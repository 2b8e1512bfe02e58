//! The renderer's kernels with the push blocks their dispatches use, for the test that checks
//! every kernel's block against the reflected GLSL.

use crate::accel::ray_queries::TraceRaysPush;
use crate::kernels::render::{PATH_TRACE, TRACE_RAYS};
use crate::render::path_tracer::PathTracePush;
use lazysolid_compute::gpu::PushRegistration;

/// The registry of the renderer's kernels (the shading test kernel is registered by the tests
/// that dispatch it).
pub fn push_registry() -> Vec<PushRegistration> {
    vec![
        PushRegistration::of::<PathTracePush>(&PATH_TRACE),
        PushRegistration::of::<TraceRaysPush>(&TRACE_RAYS),
    ]
}
