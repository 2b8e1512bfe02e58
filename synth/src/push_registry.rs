//! Every kernel of this crate with the push block its dispatches use, for the test that checks
//! each pair against the reflected GLSL (a kernel with a push block that is missing here fails
//! it too).

use crate::kernels::{synth, synth_solid};
use crate::multiscale::gpu as multiscale_gpu;
use crate::solid::lazy::gpu as lazy_gpu;
use crate::solid::lazy::visit_order as lazy_visit;
use crate::solid::lazy::walk as lazy_walk;
use crate::solid::{candidates_gpu as solid_candidates, gpu as solid_gpu};
use crate::{energy, gpu as synth_gpu};
use lazysolid_compute::gpu::{KernelDef, PushBlock, PushRegistration};

fn of<P: PushBlock>(kernel: &'static KernelDef) -> PushRegistration {
    PushRegistration::of::<P>(kernel)
}

/// The registry of `lazysolid-synth`'s kernels.
pub fn push_registry() -> Vec<PushRegistration> {
    vec![
        of::<synth_gpu::CorrectPush>(&synth::CORRECT),
        of::<energy::EnergyPush>(&synth::ENERGY),
        of::<synth_gpu::UpsamplePush>(&synth::UPSAMPLE_JITTER),
        of::<multiscale_gpu::MsUpsamplePush>(&synth::MULTISCALE_UPSAMPLE),
        of::<multiscale_gpu::MsCorrectPush>(&synth::MULTISCALE_CORRECT),
        of::<multiscale_gpu::MsCorrectPush>(&synth::MULTISCALE_CORRECT_PERIOD),
        of::<multiscale_gpu::MsCorrectPush>(&synth::MULTISCALE_CORRECT_PLAIN),
        of::<multiscale_gpu::MsCorrectPush>(&synth::MULTISCALE_CORRECT_TRANSFERS),
        of::<multiscale_gpu::MsEnterPush>(&synth::MULTISCALE_ENTER),
        of::<multiscale_gpu::MsExitPush>(&synth::MULTISCALE_EXIT),
        of::<multiscale_gpu::MsSelectPush>(&synth::MULTISCALE_SELECT),
        of::<solid_candidates::SearchPush>(&synth_solid::STRIP_SEARCH),
        of::<solid_candidates::TriplesPush>(&synth_solid::TRIPLES),
        of::<solid_candidates::CoherencePush>(&synth_solid::COHERENCE),
        of::<solid_gpu::UpsamplePush>(&synth_solid::UPSAMPLE_JITTER),
        of::<solid_gpu::CorrectPush>(&synth_solid::CORRECT),
        of::<lazy_gpu::PreparePush>(&synth_solid::LAZY_PREPARE),
        of::<lazy_gpu::AssignPush>(&synth_solid::LAZY_ASSIGN),
        of::<lazy_gpu::LazyUpsamplePush>(&synth_solid::LAZY_UPSAMPLE),
        of::<lazy_gpu::LazyCorrectPush>(&synth_solid::LAZY_CORRECT),
        of::<lazy_visit::StageRangesPush>(&synth_solid::LAZY_STAGE_RANGES),
        of::<lazy_gpu::GatherPush>(&synth_solid::LAZY_GATHER),
        of::<lazy_gpu::ColoursPush>(&synth_solid::LAZY_COLOURS),
        of::<lazy_walk::ExpandPush>(&synth_solid::LAZY_DEPS_EXPAND),
        of::<lazy_walk::TaggedUniquePush>(&synth_solid::LAZY_DEPS_UNIQUE),
        of::<lazy_walk::ParentsPush>(&synth_solid::LAZY_DEPS_PARENTS),
        of::<lazy_walk::WalkStepPush>(&synth_solid::LAZY_WALK_STEP),
    ]
}
