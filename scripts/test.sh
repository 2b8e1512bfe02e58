#!/usr/bin/env bash
# The whole test suite, as CI runs it: installs what is needed, checks formatting and lints,
# then runs every test on the default device with the Vulkan validation layer required.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-assets.sh
export LAZYSOLID_VALIDATION=1
cargo fmt --all -- --check
cargo clippy --locked --workspace --all-targets -- -D warnings
cargo test --locked --workspace
