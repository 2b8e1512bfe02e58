#!/usr/bin/env bash
# Puts real test meshes into assets/meshes/ (git-ignored) without committing third-party data:
# Debian's libcgal-demo package ships CGAL's data.tar.gz, whose data/meshes/ holds the
# armadillo (26,002 vertices, 52,000 triangles), bunny, Chinese dragon and others as OFF files,
# which lazysolid reads directly.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=assets/meshes
meshes=(armadillo.off bunny00.off ChineseDragon-10kv.off elephant.off cube.off)

have_all=1
for m in "${meshes[@]}"; do [ -s "$dest/$m" ] || have_all=0; done
if [ "$have_all" = 1 ]; then
  echo "fetch-assets: meshes already in $dest"
  exit 0
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1) || {
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  (cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1)
}
deb=$(ls "$work"/libcgal-demo_*.deb)
dpkg-deb -x "$deb" "$work/root"
tarball="$work/root/usr/share/doc/libcgal-dev/data.tar.gz"
[ -f "$tarball" ] || { echo "fetch-assets: $deb has no data.tar.gz" >&2; exit 1; }
tar -xzf "$tarball" -C "$work" $(printf 'data/meshes/%s ' "${meshes[@]}")
mkdir -p "$dest"
for m in "${meshes[@]}"; do
  # Copy through a temporary name so an interrupted run leaves no half file.
  cp "$work/data/meshes/$m" "$dest/.$m.partial" && mv "$dest/.$m.partial" "$dest/$m"
done
echo "fetch-assets: $(ls "$dest" | wc -l) meshes from $(basename "$deb") in $dest"
