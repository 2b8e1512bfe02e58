#!/usr/bin/env bash
# Installs the Debian 12 packages lazysolid needs to build and run, and checks the Rust toolchain.
#   fonts-dejavu-core is the font of the benchmark plots.
#   lavapipe (Mesa's CPU Vulkan driver), the Vulkan loader and the Khronos validation layer;
#   shaderc, glslang and SPIRV-Tools with their static archives (Debian's libshaderc.so cannot be
#   linked, so build.rs links libshaderc_combined.a with the static glslang/SPIRV-Tools ones).
#   With --tests (scripts/test.sh), also what the tests check exports with: blender (3.4, with
#   python3-numpy for its glTF importer) and Node with npm, and the Khronos glTF validator,
#   installed into the user's cache (scripts/gltf-validate.sh --install). The main job needs
#   none of them.
#
# LAZYSOLID_MESA=backports installs lavapipe from bookworm-backports (Mesa 25) instead of
# bookworm's Mesa 22: about 2x faster on lazysolid's kernels (docs/compute-core.md), but it also
# upgrades the system's libdrm and Mesa GL drivers. CI uses bookworm's.
set -euo pipefail

packages=(
  mesa-vulkan-drivers libvulkan1 libvulkan-dev vulkan-tools vulkan-validationlayers
  libshaderc-dev glslang-dev glslang-tools spirv-tools
  build-essential pkg-config git ca-certificates xz-utils fonts-dejavu-core
)
tests=false
case "${1:-}" in
  --tests) tests=true ;;
  "") ;;
  *) echo "install-deps: unknown option $1 (only --tests)" >&2; exit 1 ;;
esac
if $tests; then
  packages+=(blender python3-numpy)
  # Node 18 from Debian where no node is on the PATH (a newer one, if present, is kept).
  command -v node >/dev/null || packages+=(nodejs)
  command -v npm >/dev/null || packages+=(npm)
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  sudo="sudo"
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ "${LAZYSOLID_MESA:-}" = "backports" ]; then
  if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    printf 'Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
      | $sudo tee /etc/apt/sources.list.d/bookworm-backports.sources >/dev/null
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq -t bookworm-backports mesa-vulkan-drivers >/dev/null
  echo "install-deps: lavapipe from bookworm-backports: $(dpkg-query -W -f='${Version}' mesa-vulkan-drivers)"
elif [ -n "${LAZYSOLID_MESA:-}" ]; then
  echo "install-deps: LAZYSOLID_MESA=${LAZYSOLID_MESA} is not understood (only 'backports')" >&2
  exit 1
fi

if $tests; then
  bash "$(dirname "$0")/gltf-validate.sh" --install
fi

if ! command -v cargo >/dev/null; then
  echo "install-deps: cargo not found; lazysolid needs Rust 1.85 or newer (rustup.rs)" >&2
  exit 1
fi
echo "install-deps: system packages present; $(cargo --version)"
