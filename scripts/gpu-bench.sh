#!/usr/bin/env bash
# Everything lazysolid measures, in one run on the first non-CPU Vulkan device: `device`, the
# test subset (scripts/test-subset.sh) and every bench suite at the sizes the papers use, each
# under a time limit, all results under one folder. Written for a GPU lent for minutes: the
# limits add up to 10 min 40 s; a suite over its limit is stopped and the run goes on. See
# docs/gpu.md.
#
#   bash scripts/gpu-bench.sh [--quick] [--bin PATH] [--out-dir DIR] [--device NAME|INDEX]
#                             [--suites LIST] [--skip-tests] [--check-args]
#
#   --quick          small sizes, and the CPU driver (lavapipe) when no GPU is present: what
#                    CI runs to keep this script working (a few minutes on 2 cores)
#   --bin PATH       use this lazysolid executable instead of building one in release (also
#                    LAZYSOLID_BIN); the test subset then runs in cargo's dev profile
#   --out-dir DIR    results folder [results/gpu-bench-<UTC time>]
#   --device D       device name part or index [the first non-CPU device]
#   --suites LIST    comma-separated steps of: device, tests, prims, hash, psh, textures,
#                    solid, lazy, cuts, trace, synth, glints, multiscale, normalmaps, ctree
#                    [all]
#   --skip-tests     leave out the test subset (CI runs it separately)
#   --check-args     run nothing: check that every suite's quick and full options parse
#                    (`lazysolid bench SUITE OPTIONS --help` fails on any that does not), in
#                    seconds; CI's command-line tests run every suite at small sizes
#
# Writes DIR/summary.csv (step, status, seconds, limit, files), DIR/<step>.log and each suite's
# CSV, JSON and figures in DIR/<suite>/. Exits 1 if any step failed or ran out of time.
set -euo pipefail
cd "$(dirname "$0")/.."

SUITES=(prims hash psh textures solid lazy cuts trace synth glints multiscale normalmaps ctree)
# Seconds per step in the full run: each suite's lavapipe time scaled by the thesis' GPU
# speed-ups, plus its CPU baselines, which no GPU speeds up (docs/gpu.md has the estimate per
# suite). They sum to 640 s.
declare -A LIMIT=(
  [device]=10 [tests]=70 [prims]=25 [hash]=55 [psh]=40 [textures]=50 [solid]=60 [lazy]=90
  [cuts]=30 [trace]=15 [synth]=90 [glints]=30 [multiscale]=20 [normalmaps]=15 [ctree]=40
)
# Seconds per suite in the quick run: only a guard against a hang (the quick run takes about
# 5 minutes on lavapipe with 2 cores, the debug build and validation; the tests 30 minutes).
QUICK_LIMIT=400
# The full run: the papers' sizes (most are the suites' defaults, named here so that a later
# change of a default does not silently change what the GPU tables mean).
declare -A FULL=(
  [prims]="--scan-elements 67108864 --sort-elements 16777216"
  [hash]="--image-res 4096x4096 --voxel-res 512 --random-keys 1048576"
  [psh]="--voxel-res 256,1024 --image-res 400x400"
  [textures]="--voxel-res 1024 --res 800x800"
  [solid]="--exemplars terra,brick --candidate-sides 64,128 --voxel-res 64,128"
  [lazy]="--meshes armadillo --voxel-res 1024"
  [cuts]="--voxel-res 256 --pieces 8,32"
  [trace]="--res 1024x1024"
  [synth]="--exemplars leather --res 256,512 --quality-seeds 1"
  [glints]="--res 128,256,512"
  [multiscale]="--res 256"
  [normalmaps]="--res 320x240 --spp 1,4,16 --reference-spp 256 --fit-sizes 128,256,512"
  [ctree]="--size 1024 --volume 256 --lookups 16777216"
)
# The quick run: each suite's smallest meaningful case, one run, no warm-up. Exemplar analysis
# and candidate precompute grow with the exemplar, so lazy and cuts take a 16² exemplar
# (@SMALL_EXEMPLAR@, synthesized from terra) and multiscale a loop graph of the 64² terra
# (@TERRA_LOOP@) instead of the 128² marble: both written into the results folder.
declare -A QUICK=(
  [prims]="--quick --scan-elements 1048576 --sort-elements 262144"
  [hash]="--quick --load-factors 0.5,0.9 --datasets random-2d,voxels"
  [psh]="--quick --voxel-res 64 --blocked-voxel-res 64"
  [textures]="--voxel-res 64 --res 64x64 --mesh bunny00"
  [solid]="--quick --exemplars terra --three= --candidate-sides 16 --side 16 --voxel-res 16 --passes 1 --energy-samples 64"
  [lazy]="--quick --meshes bunny00 --voxel-res 16 --exemplar @SMALL_EXEMPLAR@"
  [cuts]="--mesh elephant --voxel-res 32 --pieces 4 --exemplar @SMALL_EXEMPLAR@"
  [trace]="--mesh bunny00 --res 64x64"
  [synth]="--quick --exemplars leather --res 64 --quality-seeds 1 --energy-samples 256"
  [glints]="--quick --res 32 --queries 500 --coverage 512 --render-res 32x24 --spp 1"
  [multiscale]="--graphs @TERRA_LOOP@ --res 64 --deeper 1 --quality-res 32 --energy-samples 64"
  [normalmaps]="--res 32x24 --spp 1 --reference-spp 4 --fit-sizes 16 --lobes 4"
  [ctree]="--quick --lookups 65536"
)

usage() { sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; }
die() { echo "gpu-bench: $*" >&2; exit 2; }

quick=0
bin="${LAZYSOLID_BIN:-}"
out=""
device=""
only=""
skip_tests=0
check_args=0
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --bin) [ $# -ge 2 ] || die "--bin needs a path"; bin="$2"; shift ;;
    --out-dir) [ $# -ge 2 ] || die "--out-dir needs a folder"; out="$2"; shift ;;
    --device) [ $# -ge 2 ] || die "--device needs a name or index"; device="$2"; shift ;;
    --suites) [ $# -ge 2 ] || die "--suites needs a list"; only="$2"; shift ;;
    --skip-tests) skip_tests=1 ;;
    --check-args) check_args=1 ;;
    -h|--help) usage; exit 0 ;;
    *) usage >&2; die "unknown option $1" ;;
  esac
  shift
done

steps=(device tests "${SUITES[@]}")
if [ -n "$only" ]; then
  IFS=',' read -r -a wanted <<<"$only"
  for w in "${wanted[@]}"; do
    [ -n "${LIMIT[$w]:-}" ] || die "--suites: unknown step $w; known: ${steps[*]}"
  done
  steps=("${wanted[@]}")
fi
if [ "$skip_tests" = 1 ]; then
  kept=()
  for s in "${steps[@]}"; do [ "$s" = tests ] || kept+=("$s"); done
  steps=("${kept[@]}")
fi

target="${CARGO_TARGET_DIR:-target}"
test_profile=()
if [ -z "$bin" ]; then
  echo "gpu-bench: building lazysolid in release"
  cargo build --locked --release -p lazysolid-tools
  bin="$target/release/lazysolid"
  test_profile=(--release)
fi
[ -x "$bin" ] || die "--bin $bin is not an executable"
bin="$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")"

# Placeholders of the size options, replaced by the files the run writes (see QUICK).
placeholders() {
  local sizes="$1" dir="$2"
  sizes="${sizes//@SMALL_EXEMPLAR@/$dir/terra16.png}"
  echo "${sizes//@TERRA_LOOP@/$dir/terra_loop.toml}"
}

if [ "$check_args" = 1 ]; then
  bad=0
  for suite in "${SUITES[@]}"; do
    for mode in quick full; do
      if [ "$mode" = quick ]; then sizes="${QUICK[$suite]}"; runs="--runs 1 --warmup 0"; else
        sizes="${FULL[$suite]}"; runs="--runs 3 --warmup 1"; fi
      sizes="$(placeholders "$sizes" /tmp)"
      # shellcheck disable=SC2086 # the size options are words on purpose
      if ! err="$("$bin" bench "$suite" $sizes $runs --help 2>&1 >/dev/null)"; then
        echo "gpu-bench: the $mode options of $suite do not parse: $sizes" >&2
        echo "$err" | sed 's/^/  /' >&2
        bad=1
      fi
    done
  done
  [ "$bad" = 0 ] && echo "gpu-bench: the quick and full options of ${#SUITES[@]} suites parse"
  exit "$bad"
fi

# The device: the one named, else the first usable non-CPU device, else (quick only) the CPU
# driver. `lazysolid device` prints "device N: NAME" and then "  type  KIND" per device.
if [ -z "$device" ]; then
  listing="$("$bin" device)" || die "lazysolid device failed: no Vulkan device"
  device="$(awk '/^device [0-9]+:/ { idx = $2; sub(":", "", idx) }
                /^  type / && $2 != "cpu" && idx != "" { print idx; exit }' <<<"$listing")"
  if [ -z "$device" ]; then
    [ "$quick" = 1 ] || die "no GPU found (lazysolid device lists only CPU devices); --quick runs on lavapipe, --device picks one"
    device="$(awk '/^device [0-9]+:/ { idx = $2; sub(":", "", idx); print idx; exit }' <<<"$listing")"
  fi
fi
export LAZYSOLID_DEVICE="$device"

if [ -z "$out" ]; then
  out="results/gpu-bench-$(date -u +%Y%m%dT%H%M%SZ)"
fi
mkdir -p "$out"
out="$(cd "$out" && pwd)"
summary="$out/summary.csv"
echo "step,status,seconds,limit_s,files" >"$summary"

# Measured runs: 3 after 1 warm-up (1 and none for lazy, whose one run at 1024³ is long), and
# 1 without warm-up in the quick run.
runs_of() {
  if [ "$quick" = 1 ] || [ "$1" = lazy ]; then echo "--runs 1 --warmup 0"; else echo "--runs 3 --warmup 1"; fi
}
if [ "$quick" = 1 ]; then
  # lavapipe is slow and CI has the time to validate: every error fails the step (exit 2).
  export LAZYSOLID_VALIDATION=1
fi

failed=0
# Runs step $1 under its time limit with the command that follows; records the outcome.
run_step() {
  local step="$1"; shift
  local limit="${LIMIT[$step]}"
  if [ "$quick" = 1 ]; then
    limit=$QUICK_LIMIT
    # The subset on lavapipe takes about 10 minutes.
    [ "$step" = tests ] && limit=1800
  fi
  local start end status code=0 files=""
  echo "gpu-bench: $step (limit ${limit} s)"
  start=$(date +%s%N)
  timeout --kill-after=10 "$limit" "$@" >"$out/$step.log" 2>&1 || code=$?
  end=$(date +%s%N)
  case "$code" in
    0) status=ok ;;
    124|137) status=timeout ;;
    *) status="failed($code)" ;;
  esac
  if [ -d "$out/$step" ]; then
    files="$(cd "$out/$step" && ls -- *.csv 2>/dev/null | tr '\n' ' ' | sed 's/ $//' || true)"
    if [ "$status" = ok ] && [ -z "$files" ]; then
      status="no-csv"
    fi
  fi
  [ "$status" = ok ] || { failed=1; tail -n 20 "$out/$step.log" | sed "s/^/  $step: /" >&2; }
  local tenths=$(((end - start) / 100000000))
  printf '%s,%s,%d.%d,%s,"%s"\n' "$step" "$status" $((tenths / 10)) $((tenths % 10)) "$limit" "$files" >>"$summary"
  echo "gpu-bench: $step $status"
}

for step in "${steps[@]}"; do
  case "$step" in
    device)
      run_step device "$bin" device ;;
    tests)
      # Built before its timer starts: the limit is for running the tests.
      bash scripts/test-subset.sh "${test_profile[@]}" --no-run >"$out/tests-build.log" 2>&1 \
        || die "building the test subset failed; see $out/tests-build.log"
      run_step tests bash scripts/test-subset.sh "${test_profile[@]}" ;;
    *)
      mkdir -p "$out/$step"
      if [ "$quick" = 1 ]; then sizes="${QUICK[$step]}"; else sizes="${FULL[$step]}"; fi
      if [[ "$sizes" == *@SMALL_EXEMPLAR@* ]]; then
        if [ ! -f "$out/terra16.png" ]; then
          "$bin" synth terra --res 16x16 --seed 1 -o "$out/terra16.png" >"$out/terra16.log" 2>&1 \
            || die "synthesizing the quick run's 16² exemplar failed; see $out/terra16.log"
        fi
      fi
      if [[ "$sizes" == *@TERRA_LOOP@* ]]; then
        printf 'root = "terra"\n\n[[exemplar]]\nname = "terra"\nimage = "terra"\n\n[[edge]]\nsource = "terra"\ndestination = "terra"\nr = 1\n' \
          >"$out/terra_loop.toml"
      fi
      sizes="$(placeholders "$sizes" "$out")"
      # shellcheck disable=SC2086 # the size options are words on purpose
      run_step "$step" "$bin" bench "$step" $sizes $(runs_of "$step") --out-dir "$out/$step" ;;
  esac
done

echo
column -s, -t <"$summary" 2>/dev/null || cat "$summary"
echo "gpu-bench: results in $out"
exit "$failed"
