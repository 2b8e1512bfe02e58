#!/usr/bin/env bash
# The main job: installs what is needed, builds, and path-traces the default scene on the
# default device (lavapipe when no GPU is present), then says where the images are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-assets.sh
cargo build --release --locked -p lazysolid-tools
bin=target/release/lazysolid
"$bin" device
mkdir -p results
"$bin" render scenes/default.toml -o results/default.png
echo
echo "The rendered image is $(pwd)/results/default.png (HDR with albedo, normal and depth: $(pwd)/results/default.exr)"
