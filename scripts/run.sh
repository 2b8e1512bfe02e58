#!/usr/bin/env bash
# The main job: installs what is needed, builds, and runs lazysolid on the default device
# (lavapipe when no GPU is present). For now: the device listing and the primitive benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-assets.sh
cargo build --release --locked -p lazysolid-tools
bin=target/release/lazysolid
"$bin" device
"$bin" bench prims --runs 3 --out results
echo
echo "Benchmark tables are in $(pwd)/results (CSV and JSON, newest last):"
ls -1 results/bench-prims-* | tail -2
