#!/usr/bin/env bash
# The whole test suite, as CI runs it: installs what is needed, checks formatting and lints,
# builds the API docs with every link resolved, then runs every test on the default device
# with the Vulkan validation layer required.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each step prints its time, so a run shows where the suite's time goes (docs/testing.md).
step() {
  local name="$1" start=$SECONDS
  shift
  "$@"
  echo "test.sh: ${name} took $((SECONDS - start)) s (${SECONDS} s so far)"
}
step "install" bash scripts/install-deps.sh --tests
step "assets" bash scripts/fetch-assets.sh
export LAZYSOLID_VALIDATION=1
step "fmt" cargo fmt --all -- --check
# Every intra-doc link resolves (a renamed or private item breaks it silently otherwise).
RUSTDOCFLAGS="-D warnings" step "API docs" cargo doc --locked --workspace --no-deps
# Clippy's lints run while the tests are built: the workspace's crates are compiled by
# clippy-driver with warnings denied, which lints every target `cargo clippy --all-targets`
# does (libraries, binaries, tests, examples, build scripts) in the same compile. Exported, so
# the steps below reuse these builds instead of compiling the crates again.
export RUSTC_WORKSPACE_WRAPPER="$PWD/scripts/lint-rustc.sh"
step "building the tests, with Clippy's lints" cargo test --locked --workspace --no-run
step "cargo test" cargo test --locked --workspace
# The subset again under the two settings a GPU differs by, in one run since they are
# independent (one changes how bytes reach memory, the other the width kernels run at): every
# upload and readback through a staging buffer, as a discrete GPU's memory requires, and
# lavapipe at 128 bits, whose subgroups of 4 instead of 8 show any kernel that depends on 8
# lanes (docs/gpu.md). Reuses the binaries built above. The fracture test through every store
# is left out: it bakes the same stores through the same kernels as the frame references and
# the store tests.
LAZYSOLID_MEMORY=device-local LP_NATIVE_VECTOR_WIDTH=128 step "the subset, GPU settings" \
  bash scripts/test-subset.sh -- --skip fracture_through_every_store
# scripts/gpu-bench.sh stays runnable, on the debug executable the tests built (no release
# build): every suite's quick and full options parse, and the suites that no command-line
# test runs (tools/tests/cli/bench/) run at quick sizes on lavapipe through the script.
bin="${CARGO_TARGET_DIR:-target}/debug/lazysolid"
step "gpu-bench.sh options" bash scripts/gpu-bench.sh --check-args --bin "$bin"
bench_out="$(mktemp -d)"
step "gpu-bench.sh --quick" bash scripts/gpu-bench.sh --quick --skip-tests \
  --suites device,trace,multiscale --bin "$bin" --out-dir "$bench_out"
rm -rf "$bench_out"
