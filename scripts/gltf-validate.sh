#!/usr/bin/env bash
# Runs the Khronos glTF validator (npm `gltf-validator`, pinned below) on glTF binaries: prints
# each file's error, warning, info and hint counts and its errors and warnings, and fails when
# any file has an error. `--install` only installs the validator (scripts/install-deps.sh calls
# it, so tests need no network). The validator lives in the user's cache, not in the repository.
#   bash scripts/gltf-validate.sh [--install] [FILE.glb ...]
set -euo pipefail
version="2.0.0-dev.3.10"
dir="${XDG_CACHE_HOME:-$HOME/.cache}/lazysolid/gltf-validator-${version}"
if [ ! -f "$dir/node_modules/gltf-validator/package.json" ]; then
  command -v npm >/dev/null || { echo "gltf-validate: npm not found (bash scripts/install-deps.sh --tests installs it)" >&2; exit 1; }
  mkdir -p "$dir"
  npm install --silent --no-audit --no-fund --prefix "$dir" "gltf-validator@${version}" >/dev/null
fi
if [ "${1:-}" = "--install" ]; then
  echo "gltf-validate: gltf-validator ${version} in $dir"
  exit 0
fi
GLTF_VALIDATOR_DIR="$dir/node_modules" exec node "$(dirname "$0")/gltf-validate.mjs" "$@"
