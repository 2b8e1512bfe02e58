#!/usr/bin/env bash
# The representative subset of the suite that runs under other device settings: the Vulkan
# core, the primitives, the hashes, the stores, solid and lazy synthesis and the renderer, each
# GPU kernel against its CPU reference with validation required. CI runs it once with both of
# its settings together (LAZYSOLID_MEMORY=device-local and LP_NATIVE_VECTOR_WIDTH=128, see
# scripts/test.sh); scripts/gpu-bench.sh runs it on the GPU. The test binaries are the ones
# `cargo test --workspace` builds, so in CI this compiles nothing new.
#
#   bash scripts/test-subset.sh [CARGO TEST ARGS...]   e.g. --release
set -euo pipefail
cd "$(dirname "$0")/.."
# One list, read by scripts/gpu-bench.sh too.
SUBSET_TESTS=(core prims hash store store_samples tiletree solid lazy render)
# Tests of those binaries that never create a device: a device setting cannot change what
# they check, so the subset leaves them to the main run (minutes of CPU references).
HOST_ONLY=(
  usage_balance_evens_out_what_the_volume_uses
  candidates_round_trip_through_the_disk_cache
  mirroring_one_role_keeps_the_diagonal_of_the_veins
  lazy_equals_the_full_volume_on_every_request_set
  two_batches_equal_one_request_of_their_union_in_either_order
  dependency_sets_cover_only_what_is_needed
  timestamp_differences_wrap_at_the_valid_bits_and_scale_by_the_period
  the_sample_gradient_is_the_derivative_of_the_trilinear_alpha
  folds_split_leaves_until_each_face_projects_injectively
)
# Tests whose device work another test of the subset runs through the same kernels and the
# same uploads and read-backs: what they add is host logic (a memory policy's bookkeeping, a
# camera's lens, the host candidate builder's pruning against its CPU reference), which a
# device setting cannot change. They stay in the main run.
DEVICE_REPEATS=(
  every_memory_policy_returns_the_full_volume_and_recomputes_what_it_dropped
  thin_lens_blurs_only_out_of_focus
  host_candidates_equal_the_reference
)
args=()
for t in "${SUBSET_TESTS[@]}"; do
  args+=(--test "$t")
done
# Arguments after `--` go to the test binaries: the host-only skips join them.
harness=()
for t in "${HOST_ONLY[@]}" "${DEVICE_REPEATS[@]}"; do
  harness+=(--skip "$t")
done
cargo_args=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  cargo_args+=("$1")
  shift
done
[ $# -gt 0 ] && shift
export LAZYSOLID_VALIDATION=1
# --workspace, not -p: the same feature set as `cargo test --workspace`, so nothing rebuilds.
exec cargo test --locked --workspace "${args[@]}" "${cargo_args[@]}" -- "${harness[@]}" "$@"
