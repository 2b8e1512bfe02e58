#!/usr/bin/env bash
# The representative subset of the suite that runs under other device settings: the Vulkan
# core, the primitives, the hashes, the stores, solid and lazy synthesis and the renderer, each
# GPU kernel against its CPU reference with validation required. CI runs it once with both of
# its settings together (LAZYSOLID_MEMORY=device-local and LP_NATIVE_VECTOR_WIDTH=128, see
# scripts/test.sh); scripts/gpu-bench.sh runs it on the GPU. The test binary is the one
# `cargo test --workspace` builds, so in CI this compiles nothing new.
#
#   bash scripts/test-subset.sh [CARGO TEST ARGS...]   e.g. --release
set -euo pipefail
cd "$(dirname "$0")/.."
# The modules of the integration test binary (tests/tests/<name>.rs) the subset runs; one
# list, read by scripts/gpu-bench.sh too.
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
# camera's lens, the host candidate builder's pruning against its CPU reference, a render's
# seed, the store records' refresh after an insert), which a device setting cannot change.
# They stay in the main run.
DEVICE_REPEATS=(
  every_memory_policy_returns_the_full_volume_and_recomputes_what_it_dropped
  thin_lens_blurs_only_out_of_focus
  host_candidates_equal_the_reference
  same_seed_same_image_other_seed_other_image
  store_records_follow_inserts
)
cargo_args=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  cargo_args+=("$1")
  shift
done
[ $# -gt 0 ] && shift
# Arguments after `--` go to the test binary; `--skip NAME` among them leaves out the tests
# whose names contain NAME, as libtest's own `--skip` does, with the host-only and repeated
# tests above.
skips=("${HOST_ONLY[@]}" "${DEVICE_REPEATS[@]}")
harness=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--skip" ] && [ $# -gt 1 ]; then
    skips+=("$2")
    shift 2
  else
    harness+=("$1")
    shift
  fi
done
export LAZYSOLID_VALIDATION=1
# --workspace, not -p: the same feature set as `cargo test --workspace`, so nothing rebuilds.
run=(cargo test --locked --workspace --test integration "${cargo_args[@]}")
# Only building (`--no-run`, as scripts/gpu-bench.sh does first): there is nothing to pick.
for a in "${cargo_args[@]}"; do
  [ "$a" = "--no-run" ] && exec "${run[@]}"
done
# The subset's tests by their full names: a name starts with its module's path, and a
# libtest filter matches anywhere in a name (`hash::` would also match `perfect_hash::…`),
# so the names are picked here and run with `--exact`.
names=()
listing="$("${run[@]}" -- --list --format terse)"
while IFS= read -r line; do
  name="${line%: test}"
  [ "$name" != "$line" ] || continue
  module="${name%%::*}"
  printf '%s\n' "${SUBSET_TESTS[@]}" | grep -qxF -- "$module" || continue
  for skip in "${skips[@]}"; do
    [[ "$name" == *"$skip"* ]] && continue 2
  done
  names+=("$name")
done <<<"$listing"
[ ${#names[@]} -gt 0 ] || { echo "test-subset.sh: no test of the subset found" >&2; exit 1; }
echo "test-subset.sh: ${#names[@]} tests of the modules ${SUBSET_TESTS[*]}"
exec "${run[@]}" -- --exact "${names[@]}" "${harness[@]}"
