#!/usr/bin/env bash
# Weidner & Linsen's Tables 3 and 4 for penumbra: map generation time (a
# prepare() after a TF change rebuilds every map) at 1024^2, 2048^2 and
# 4096^2, frame time (prepare() + render(), the camera orbiting, maps reused)
# and memory per map, for shadow-map, deep-shadow-map (3 nodes) and cssm (13
# offsets) on the engine CT and the head CT with a point light, plus
# shadow-rays for scale and, at GREY_RESOLUTION, the deep shadow map and the
# CSSM without transport colour (colored=false: a light ray ends where it
# gets opaque, not where every channel does). Prints markdown rows: medians
# over RUNS runs of `penumbra bench` (each itself a median of 3 rebuilds and
# FRAMES frames). Then, unless NO_COMPARE is set, `penumbra compare` of the
# three against shadow-rays on both scenes, with and without transport
# colour (images, dE maps, report.md under OUT).
#
# Usage: scripts/bench-shadow-maps.sh [RUNS]     (default 1)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   SIZE=512x512 FRAMES=3 RESOLUTIONS="1024 2048 4096" GREY_RESOLUTION=1024
#   OUT=/tmp/bench-shadow-maps
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
runs=${1:-1}
size=${SIZE:-512x512}
frames=${FRAMES:-3}
resolutions=${RESOLUTIONS-1024 2048 4096}
grey_resolution=${GREY_RESOLUTION-1024}
out=${OUT:-/tmp/bench-shadow-maps}
mkdir -p "$out"
summarise() {
  python3 -c "
import json, sys, statistics
rows = [json.loads(line) for line in sys.stdin if line.startswith('{')]
med = lambda key: statistics.median(r[key] for r in rows)
print('| $1 | $2 | $3 | {:.0f} | {:.0f} | {:.1f} |'.format(med('tf_change_ms'), med('frame_ms_median'), rows[0]['aux_bytes'] / 2**20))"
}
echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg), image $size"
echo "| scene | technique | map | generation ms | frame ms | memory MiB |"
echo "|---|---|---|---|---|---|"
for scene in engine-point head-point; do
  for resolution in $resolutions; do
    for technique in shadow-map deep-shadow-map cssm; do
      for _ in $(seq "$runs"); do
        "$bin" bench "$root/scenes/$scene.json" --technique $technique --param resolution=$resolution \
          --frames "$frames" --size "$size"
      done | summarise $scene $technique "${resolution}^2"
    done
  done
  for technique in ${grey_resolution:+deep-shadow-map cssm}; do
    for _ in $(seq "$runs"); do
      "$bin" bench "$root/scenes/$scene.json" --technique $technique --param resolution=$grey_resolution \
        --param colored=false --frames "$frames" --size "$size"
    done | summarise $scene "$technique, colored=false" "${grey_resolution}^2"
  done
  for _ in $(seq "$runs"); do
    "$bin" bench "$root/scenes/$scene.json" --technique shadow-rays --frames "$frames" --size "$size"
  done | summarise $scene shadow-rays "-"
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -z "${NO_COMPARE:-}" ]; then
  for scene in engine-point head-point; do
    for colored in true false; do
      "$bin" compare "$root/scenes/$scene.json" --techniques shadow-map,deep-shadow-map,cssm --reference shadow-rays \
        --param colored=$colored --size 256x256 --frames 1 -o "$out/$scene-colored-$colored" > /dev/null
      echo "## $scene against shadow-rays, colored=$colored ($out/$scene-colored-$colored)"
      cat "$out/$scene-colored-$colored/report.md"
    done
  done
fi
