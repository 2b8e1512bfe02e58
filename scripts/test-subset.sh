#!/usr/bin/env bash
# The representative subset of the suite that runs under other device settings: the Vulkan
# core, the primitives, the hashes, the stores, solid and lazy synthesis and the renderer, each
# GPU kernel against its CPU reference with validation required. CI runs it with
# LAZYSOLID_MEMORY=device-local (every upload and readback through staging, as on a discrete
# GPU); scripts/gpu-bench.sh runs it on the GPU. The test binaries are the ones
# `cargo test --workspace` builds, so in CI this compiles nothing new.
#
#   bash scripts/test-subset.sh [CARGO TEST ARGS...]   e.g. --release
set -euo pipefail
cd "$(dirname "$0")/.."
# One list, read by scripts/gpu-bench.sh too.
SUBSET_TESTS=(core prims hash store store_samples tiletree solid lazy render)
args=()
for t in "${SUBSET_TESTS[@]}"; do
  args+=(--test "$t")
done
export LAZYSOLID_VALIDATION=1
# --workspace, not -p: the same feature set as `cargo test --workspace`, so nothing rebuilds.
exec cargo test --locked --workspace "${args[@]}" "$@"
