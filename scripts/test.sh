#!/usr/bin/env bash
# The whole test suite, as CI runs it: installs what is needed, checks formatting and lints,
# builds the API docs with every link resolved, then runs every test on the default device
# with the Vulkan validation layer required.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-assets.sh
export LAZYSOLID_VALIDATION=1
cargo fmt --all -- --check
cargo clippy --locked --workspace --all-targets -- -D warnings
# Every intra-doc link resolves (a renamed or private item breaks it silently otherwise).
RUSTDOCFLAGS="-D warnings" cargo doc --locked --workspace --no-deps
cargo test --locked --workspace
# The paths only a discrete GPU takes, on lavapipe: every upload and readback through a staging
# buffer (docs/gpu.md). Reuses the binaries built above.
LAZYSOLID_MEMORY=device-local bash scripts/test-subset.sh
# Another SIMD width: lavapipe at 128 bits runs subgroups of 4 instead of 8, so no kernel may
# depend on 8 lanes. The three fracture renders (minutes, no kernel of their own) are left out.
LP_NATIVE_VECTOR_WIDTH=128 bash scripts/test-subset.sh -- --skip fracture --skip crack
# scripts/gpu-bench.sh stays runnable: every suite at quick sizes on lavapipe, on the debug
# executable the tests built (no release build), the subset having just run.
bench_out="$(mktemp -d)"
bash scripts/gpu-bench.sh --quick --skip-tests --bin "${CARGO_TARGET_DIR:-target}/debug/lazysolid" \
  --out-dir "$bench_out"
rm -rf "$bench_out"
