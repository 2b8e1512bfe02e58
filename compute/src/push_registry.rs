//! Every kernel of this crate with the push block its dispatches use, for the test that checks
//! each pair against the reflected GLSL (a kernel with a push block that is missing here fails
//! it too). The synthesizer's and the renderer's kernels are registered by their crates.

use crate::ctree::{builder as ctree_builder, device as ctree_device, mip_texture};
use crate::gpu::{PushBlock, PushRegistration};
use crate::hash::perfect::{blocked, gpu as perfect};
use crate::hash::{cuckoo, dense, open_addressing, robin_hood, validate};
use crate::kernels::{ctree, hash, prims, store, voxel};
use crate::prims::push as prims_push;
use crate::prims::segments;
use crate::store::{colours, hash_store, octree, perfect_store, tiletree};
use crate::voxel::{gpu as voxel_gpu, key_sets, keys};

fn of<P: PushBlock>(kernel: &'static crate::gpu::KernelDef) -> PushRegistration {
    PushRegistration::of::<P>(kernel)
}

/// The registry of `lazysolid-compute`'s kernels.
pub fn push_registry() -> Vec<PushRegistration> {
    vec![
        of::<validate::CheckPush>(&hash::CHECK_KEYS),
        of::<cuckoo::InsertPush>(&hash::CUCKOO_INSERT),
        of::<cuckoo::QueryPush>(&hash::CUCKOO_QUERY),
        of::<dense::QueryPush>(&hash::DENSE_QUERY),
        of::<dense::ScatterPush>(&hash::DENSE_SCATTER),
        of::<open_addressing::AgesPush>(&hash::OPEN_ADDRESSING_AGES),
        of::<perfect::AssignPush>(&hash::PERFECT_ASSIGN),
        of::<blocked::BlockedQueryPush>(&hash::PERFECT_BLOCKED_QUERY),
        of::<perfect::ClassesPush>(&hash::PERFECT_CLASSES),
        of::<perfect::FillPush>(&hash::PERFECT_FILL),
        of::<perfect::FreeCountPush>(&hash::PERFECT_FREE_COUNT),
        of::<perfect::OrderPush>(&hash::PERFECT_ORDER),
        of::<perfect::PackPush>(&hash::PERFECT_PACK),
        of::<perfect::PreparePush>(&hash::PERFECT_PREPARE),
        of::<perfect::ProposePush>(&hash::PERFECT_PROPOSE),
        of::<perfect::QueryPush>(&hash::PERFECT_QUERY),
        of::<perfect::ScatterPush>(&hash::PERFECT_SCATTER),
        of::<perfect::VerifyPush>(&hash::PERFECT_VERIFY),
        of::<robin_hood::InsertPush>(&hash::ROBIN_HOOD_INSERT32),
        of::<robin_hood::InsertPush>(&hash::ROBIN_HOOD_INSERT64),
        of::<robin_hood::MaxAgePush>(&hash::ROBIN_HOOD_MAX_AGE32),
        of::<robin_hood::MaxAgePush>(&hash::ROBIN_HOOD_MAX_AGE64),
        of::<robin_hood::QueryPush>(&hash::ROBIN_HOOD_QUERY32),
        of::<robin_hood::QueryPush>(&hash::ROBIN_HOOD_QUERY64),
        of::<robin_hood::SetAgesPush>(&hash::ROBIN_HOOD_SET_AGES32),
        of::<robin_hood::SetAgesPush>(&hash::ROBIN_HOOD_SET_AGES64),
        of::<prims_push::CompactCountPush>(&prims::COMPACT_COUNT),
        of::<prims_push::CompactWritePush>(&prims::COMPACT_WRITE),
        of::<prims_push::CopyCountPush>(&prims::COPY_QUADS),
        of::<prims_push::CopyPush>(&prims::COPY_VEC4),
        of::<prims_push::CopyCountPush>(&prims::COPY_WORDS),
        of::<prims_push::RadixCountPush>(&prims::RADIX_COUNT),
        of::<prims_push::RadixScatterPush>(&prims::RADIX_SCATTER),
        of::<segments::ReducePush>(&prims::REDUCE_SEGMENTS),
        of::<segments::ScanPush>(&prims::SCAN_SEGMENTS),
        of::<colours::ByKeyPush>(&store::COLOURS_BY_KEY),
        of::<colours::FillPush>(&store::FILL_MARBLE),
        of::<hash_store::LookupPush>(&store::HASH_LOOKUP),
        of::<octree::AveragePush>(&store::OCTREE_AVERAGE),
        of::<octree::BuildPush>(&store::OCTREE_LINK),
        of::<octree::LookupPush>(&store::OCTREE_LOOKUP),
        of::<octree::BuildPush>(&store::OCTREE_NODES),
        of::<perfect_store::LookupPush>(&store::PERFECT_LOOKUP),
        of::<tiletree::gpu::FillPush>(&store::TILETREE_DILATE),
        of::<tiletree::gpu::LookupPush>(&store::TILETREE_LOOKUP),
        of::<tiletree::gpu::FillPush>(&store::TILETREE_SCATTER),
        of::<tiletree::gpu::FillPush>(&store::TILETREE_TEXELS),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_BLOCKS),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_CHILDREN),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_FLAGS),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_INTERNAL),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_KEYS),
        of::<ctree_device::LookupPush>(&ctree::CTREE_LOOKUP),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_MIP),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_PADS),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_PICK),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_PLACE),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_QUANTIZE),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_RESIDUALS),
        of::<ctree_builder::BuildPush>(&ctree::CTREE_SIZES),
        of::<mip_texture::MipLookupPush>(&ctree::MIP_LOOKUP),
        of::<voxel_gpu::ColumnsPush>(&voxel::COLUMNS),
        of::<voxel_gpu::DilatePush>(&voxel::DILATE),
        of::<voxel_gpu::HitsPush>(&voxel::HITS),
        of::<key_sets::KeySetPush>(&voxel::KEY_SETS),
        of::<keys::UniquePush>(&voxel::UNIQUE),
    ]
}
