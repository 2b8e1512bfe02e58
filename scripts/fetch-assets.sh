#!/usr/bin/env bash
# Puts real test data into git-ignored folders without committing third-party files:
# - assets/meshes/: Debian's libcgal-demo package ships CGAL's data.tar.gz, whose data/meshes/
#   holds the armadillo (26,002 vertices, 52,000 triangles), bunny, Chinese dragon and others
#   as OFF files, which lazysolid reads directly; cow.off (2,904 vertices, 5,804 triangles) is a
#   closed scan whose surface intersects itself, the case fracture resolves.
# - assets/exemplars/: Debian's gimp-data package ships GIMP's classic tileable patterns as
#   .pat files (read directly by lazysolid synth); a handful of varied ones is extracted.
set -euo pipefail
cd "$(dirname "$0")/.."
meshes=(armadillo.off bunny00.off ChineseDragon-10kv.off elephant.off cube.off cow.off)
# Stone, brick, wood, cloth, leather and paper, 64² to 128²; granite1 (100², grey) is the
# fine-grained stone on which the synthesizer's period repetition is checked. The second line
# holds stones of other sizes and channel counts, the "any photo as exemplar" cases (fit.rs).
patterns=(Stone/brick.pat Stone/terra.pat Wood/walnut.pat Wood/parque1.pat Fabric/burlap.pat
  Animal/leather.pat Paper/crinklepaper.pat Stone/pink_marble.pat Stone/granite1.pat
  Stone/slate.pat Stone/Craters.pat Stone/stone33.pat Stone/cracked.pat Stone/ground1.pat
  Stone/marble1.pat)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Downloads Debian package $1 into $work (no install), updating the package lists once if needed.
download() {
  (cd "$work" && apt-get download "$1" >/dev/null 2>&1) || {
    sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    (cd "$work" && apt-get download "$1" >/dev/null 2>&1)
  }
  ls "$work"/"$1"_*.deb
}

# Copies $1 to $2 through a temporary name so an interrupted run leaves no half file.
install_file() {
  cp "$1" "$(dirname "$2")/.$(basename "$2").partial" && mv "$(dirname "$2")/.$(basename "$2").partial" "$2"
}

dest=assets/meshes
have_all=1
for m in "${meshes[@]}"; do [ -s "$dest/$m" ] || have_all=0; done
if [ "$have_all" = 1 ]; then
  echo "fetch-assets: meshes already in $dest"
else
  deb=$(download libcgal-demo)
  dpkg-deb -x "$deb" "$work/cgal"
  tarball="$work/cgal/usr/share/doc/libcgal-dev/data.tar.gz"
  [ -f "$tarball" ] || { echo "fetch-assets: $deb has no data.tar.gz" >&2; exit 1; }
  tar -xzf "$tarball" -C "$work" $(printf 'data/meshes/%s ' "${meshes[@]}")
  mkdir -p "$dest"
  for m in "${meshes[@]}"; do install_file "$work/data/meshes/$m" "$dest/$m"; done
  echo "fetch-assets: $(ls "$dest" | wc -l) meshes from $(basename "$deb") in $dest"
fi

dest=assets/exemplars
have_all=1
for p in "${patterns[@]}"; do [ -s "$dest/$(basename "$p")" ] || have_all=0; done
if [ "$have_all" = 1 ]; then
  echo "fetch-assets: exemplars already in $dest"
else
  deb=$(download gimp-data)
  dpkg-deb -x "$deb" "$work/gimp"
  mkdir -p "$dest"
  for p in "${patterns[@]}"; do
    src="$work/gimp/usr/share/gimp/2.0/patterns/$p"
    [ -f "$src" ] || { echo "fetch-assets: $deb has no patterns/$p" >&2; exit 1; }
    install_file "$src" "$dest/$(basename "$p")"
  done
  echo "fetch-assets: ${#patterns[@]} exemplars from $(basename "$deb") in $dest"
fi
