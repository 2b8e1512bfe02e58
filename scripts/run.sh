#!/usr/bin/env bash
# The main job: installs what is needed, builds, and renders the default scene on the default
# device (lavapipe when no GPU is present): the armadillo breaking apart, its interior
# synthesized lazily where the cracks open — a 640x480 still and a 16-frame animation from one
# synthesis — then says where the images are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-assets.sh
cargo build --release --locked -p lazysolid-tools
bin=target/release/lazysolid
"$bin" device
mkdir -p results
start=$(date +%s)
"$bin" render scenes/explosion.toml --frame 9 --frames 0..15 -o results/explosion.png
echo
echo "Rendered in $(( $(date +%s) - start )) s:"
echo "  still (640x480):       $(pwd)/results/explosion.png (HDR with albedo, normal and depth: $(pwd)/results/explosion.exr)"
echo "  frames (320x240):      $(pwd)/results/explosion_0000.png .. explosion_0015.png"
echo "  animation (GIF):       $(pwd)/results/explosion.gif"
