#!/usr/bin/env bash
# Weidner & Linsen's Fig. 2 and their deep-shadow-map-vs-CSSM comparison as an
# experiment (issue 16): quality against two references and memory, for
#   deep-shadow-map with NODES nodes (default 2 3 4 8) and
#   cssm with OFFSETS offsets (default 7 13 21), paper filter and depth-aware,
# at map resolutions RESOLUTIONS (default 512 1024 2048), on SCENES (default
# head-point shell-point).
#
# References, rendered once per scene at SIZE:
#   converged-dsm  deep-shadow-map, 16 nodes, tolerance 0.002, bilinear,
#                  2048^2 (REF_RESOLUTION), the same colour model (a converged
#                  coloured deep shadow map: what both techniques approximate)
#   shadow-rays    the physical model's grey transmittance, marched per sample
# Every configuration is rendered once with `penumbra compare --frames 1
# --reference-image`, which also times a TF change and a light move (6 more
# map builds): the experiment is slow at 2048^2 and above on 2 cores.
#
# Output: a markdown table on stdout (mean and p99 CIEDE2000 against each
# reference, memory in MiB from aux_bytes), the compare folders under OUT.
#
# Usage: scripts/shadow-maps-fig2.sh
#   PENUMBRA=build/penumbra SIZE=192x192 OUT=/tmp/shadow-maps-fig2
#   SCENES="head-point shell-point" RESOLUTIONS="512 1024 2048" NODES="2 3 4 8" OFFSETS="7 13 21"
#   COLOR_MODEL=chromatic (or paper: the paper's transport colour; grey: colored=false, the
#   transmittance shadow-rays marches, for the fairest comparison with it)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
size=${SIZE:-192x192}
out=${OUT:-/tmp/shadow-maps-fig2}
scenes=${SCENES-head-point shell-point}
resolutions=${RESOLUTIONS-512 1024 2048}
node_counts=${NODES-2 3 4 8}
offset_counts=${OFFSETS-7 13 21}
color_model=${COLOR_MODEL:-chromatic}
ref_resolution=${REF_RESOLUTION:-2048}
if [ "$color_model" = grey ]; then color=colored=false; else color=color_model=$color_model; fi
mkdir -p "$out"

# "mean_de p99_de aux_bytes" of the technique in report.json FILE
fields() {
  python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["techniques"][0]
print(t["mean_de"], t["p99_de"], t["aux_bytes"])' "$1"
}

# compare SCENE REFNAME TECHNIQUE PARAM... -> "mean_de p99_de aux_bytes"
compare() {
  local scene=$1 ref=$2 technique=$3
  shift 3
  local dir
  dir=$out/$scene/$ref/$technique-$(echo "$@" | tr ' =' '_-')
  "$bin" compare "$root/scenes/$scene.json" --techniques "$technique" --size "$size" --frames 1 \
    --reference-image "$out/$scene/$ref.exr" $(for p in "$@"; do echo --param "$p"; done) -o "$dir" >/dev/null 2>&1
  fields "$dir/report.json"
}

echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load $(cut -d' ' -f1-3 /proc/loadavg), image $size, colour model $color_model"
echo "| scene | technique | map | mean dE vs converged DSM | p99 | mean dE vs shadow-rays | p99 | memory MiB |"
echo "|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  mkdir -p "$out/$scene"
  "$bin" render "$root/scenes/$scene.json" --technique deep-shadow-map --size "$size" \
    --param nodes=16 --param tolerance=0.002 --param filter=bilinear --param resolution="$ref_resolution" \
    --param "$color" -o "$out/$scene/converged-dsm.exr" >/dev/null 2>&1
  "$bin" render "$root/scenes/$scene.json" --technique shadow-rays --size "$size" \
    -o "$out/$scene/shadow-rays.exr" >/dev/null 2>&1
  row() {  # LABEL TECHNIQUE PARAM...
    local label=$1 technique=$2
    shift 2
    local a b
    a=$(compare "$scene" converged-dsm "$technique" "$@")
    b=$(compare "$scene" shadow-rays "$technique" "$@")
    echo "$a $b" | awk -v s="$scene" -v l="$label" \
      '{printf "| %s | %s | %.2f | %.1f | %.2f | %.1f | %.1f |\n", s, l, $1, $2, $4, $5, $3 / 2^20}'
  }
  for resolution in $resolutions; do
    for nodes in $node_counts; do
      row "deep-shadow-map $nodes nodes | $resolution²" deep-shadow-map resolution="$resolution" nodes="$nodes" "$color"
    done
    for offsets in $offset_counts; do
      for filter in paper depth-aware; do
        row "cssm $offsets offsets, $filter | $resolution²" cssm resolution="$resolution" offsets="$offsets" \
          filter="$filter" "$color"
      done
    done
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
