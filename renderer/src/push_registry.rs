//! The renderer's kernels with the push blocks their dispatches use, for the test that checks
//! every kernel's block against the reflected GLSL.

use crate::accel::ray_queries::TraceRaysPush;
use crate::glint::{GlintMinMaxMipPush, GlintRangeLevelPush, GlintRangeQueryPush};
use crate::kernels::render::{
    GLINT_MINMAX_MIP, GLINT_RANGE_LEVEL, GLINT_RANGE_QUERY, PATH_TRACE, TRACE_RAYS,
    VMF_EM_ACCUMULATE, VMF_EM_UPDATE,
};
use crate::normal_map::gpu_fit::{VmfEmAccumulatePush, VmfEmUpdatePush};
use crate::render::path_tracer::PathTracePush;
use lazysolid_compute::gpu::PushRegistration;

/// The registry of the renderer's kernels (the shading and glint test kernels are registered by
/// the tests that dispatch them).
pub fn push_registry() -> Vec<PushRegistration> {
    vec![
        PushRegistration::of::<PathTracePush>(&PATH_TRACE),
        PushRegistration::of::<TraceRaysPush>(&TRACE_RAYS),
        PushRegistration::of::<GlintRangeLevelPush>(&GLINT_RANGE_LEVEL),
        PushRegistration::of::<GlintMinMaxMipPush>(&GLINT_MINMAX_MIP),
        PushRegistration::of::<GlintRangeQueryPush>(&GLINT_RANGE_QUERY),
        PushRegistration::of::<VmfEmAccumulatePush>(&VMF_EM_ACCUMULATE),
        PushRegistration::of::<VmfEmUpdatePush>(&VMF_EM_UPDATE),
    ]
}
