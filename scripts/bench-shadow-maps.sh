#!/usr/bin/env bash
# Weidner & Linsen's Tables 3 and 4 for penumbra: shadow-map, deep-shadow-map
# (3 nodes) and cssm (13 offsets) on the engine CT and the head CT with a
# point light (scenes/engine-point.json, scenes/head-point.json: a floor
# plane receives the shadows), map resolutions 1024^2, 2048^2 and 4096^2.
#
#   generation ms  prepare() of `penumbra render` (every map built once) minus
#                  the prepare() of shadow-rays on the same scene (the shared
#                  macrocell grid and TF table, which every technique builds
#                  and which is not part of a map)
#   frame ms       the render() that follows, at SIZE (maps reused)
#   memory         aux_bytes: the maps (1 float per texel, 12 for 3 deep
#                  shadow nodes, 4 for a CSSM: 3 depths and the entry)
#
# Each cell is the median over RUNS runs. `penumbra bench` is not used: it
# rebuilds the maps 7 times per run (first prepare, 3 TF changes, 3 light
# moves), which at 4096^2 takes minutes on 2 cores. A shadow-rays frame at
# the same size is printed for scale.
#
# Then, unless NO_COMPARE is set, `penumbra compare` of the three against
# shadow-rays at 256^2 on both scenes and on scenes/shell-point.json (a blue
# translucent shell around an opaque orange core: coloured shadows), with
# colour (the chromatic model, the default since issue 16) and without
# (colored=false: the grey transmittance of the physical model, which
# shadow-rays computes): report.md, grid.png and dE images under OUT. compare times --frames frames of prepare() + render()
# and the first one builds the maps, so 3 frames make its median a frame
# with the maps reused.
#
# Usage: scripts/bench-shadow-maps.sh [RUNS]   (default 1)
#   One run took 19 minutes on the shared 2-core VM at load 9-13, which
#   should be about 4-5 minutes on a quiet one; the 4096^2 maps are half of
#   it (RESOLUTIONS="1024 2048" for a quick look).
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   SIZE=512x512 RESOLUTIONS="1024 2048 4096" SCENES="engine-point head-point" OUT=/tmp/bench-shadow-maps
#   COMPARE_SCENES="engine-point head-point shell-point"
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
runs=${1:-1}
size=${SIZE:-512x512}
resolutions=${RESOLUTIONS-1024 2048 4096}
scenes=${SCENES-engine-point head-point}
compare_scenes=${COMPARE_SCENES-$scenes shell-point}
out=${OUT:-/tmp/bench-shadow-maps}
mkdir -p "$out"

# render SCENE TECHNIQUE [--param k=v]... -> "prepare_ms frame_ms" (stderr line of penumbra render)
render_times() {
  local scene=$1 technique=$2
  shift 2
  "$bin" render "$root/scenes/$scene.json" --technique "$technique" "$@" --size "$size" -o "$out/last.png" 2>&1 >/dev/null |
    sed -n 's/.*prepare \([0-9.]*\) ms, frame \([0-9.]*\) ms.*/\1 \2/p'
}
# median of column $1 of stdin
median() { sort -g -k"$1,$1" | awk -v c="$1" '{v[NR] = $c} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg), image $size, $runs run(s)"
echo "| scene | technique | map | generation ms | frame ms | memory MiB |"
echo "|---|---|---|---|---|---|"
for scene in $scenes; do
  base=$(for _ in $(seq "$runs"); do render_times "$scene" shadow-rays; done)
  base_prepare=$(echo "$base" | median 1)
  for resolution in $resolutions; do
    for technique in shadow-map deep-shadow-map cssm; do
      times=$(for _ in $(seq "$runs"); do render_times "$scene" $technique --param resolution=$resolution; done)
      case $technique in shadow-map) floats=1 ;; deep-shadow-map) floats=12 ;; cssm) floats=4 ;; esac
      awk -v s="$scene" -v t="$technique" -v r="$resolution" -v p="$(echo "$times" | median 1)" -v b="$base_prepare" \
        -v f="$(echo "$times" | median 2)" -v n="$floats" \
        'BEGIN {printf "| %s | %s | %d^2 | %.0f | %.0f | %.1f |\n", s, t, r, p - b, f, r * r * n * 4 / 2^20}'
    done
  done
  printf '| %s | shadow-rays | - | - | %.0f | 0 |\n' "$scene" "$(echo "$base" | median 2)"
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"

if [ -z "${NO_COMPARE:-}" ]; then
  for scene in $compare_scenes; do
    dir=$out/$scene
    "$bin" compare "$root/scenes/$scene.json" --techniques shadow-map,deep-shadow-map,cssm --reference shadow-rays \
      --size 256x256 --frames 3 -o "$dir-colored" >/dev/null
    # The same shadow-rays reference, without colour.
    "$bin" compare "$root/scenes/$scene.json" --techniques deep-shadow-map,cssm --param colored=false \
      --reference-image "$dir-colored/reference.exr" --size 256x256 --frames 3 -o "$dir-grey" >/dev/null
    for variant in colored grey; do
      echo "## $scene against shadow-rays, $variant ($dir-$variant)"
      grep '^|' "$dir-$variant/report.md"
    done
  done
fi
