#!/usr/bin/env bash
# shadow-rays with light samples against the path tracer on one area-light
# scene (issue 18): scenes/shell-directional.json with its light made a
# distant uniform light of half-angle ANGLE degrees (default 4), SIZE^2 pixels
# (default 128). Renders a converged single-scattering pathtrace reference
# (adaptive, 0.4 L* standard error per pixel), then `penumbra compare`s
# against it shadow-rays with 1, 4, 16 and 64 light samples and pathtrace at
# 16, 64 and 256 paths per pixel. Prints one markdown row per case: mean and
# p99 CIEDE2000 against the reference and the median frame ms of RUNS
# compare runs.
#
# Usage: scripts/bench-shadow-rays-area.sh [RUNS]     (default 3)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   ANGLE=4 SIZE=128
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
runs=${1:-3}
angle=${ANGLE:-4}
size=${SIZE:-128}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$root/scenes/shell-directional.json" "$work/scene.json" "$angle" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
light = scene["lights"][0]
scene["lights"] = [{"type": "distant", "profile": "uniform", "angle_deg": float(sys.argv[3]),
                    "direction": light["direction"], "intensity": light["intensity"]}]
json.dump(scene, open(sys.argv[2], "w"))
PY
echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg), ${size}^2, angle ${angle} deg"
start=$(date +%s)
"$bin" compare "$work/scene.json" --size "${size}x${size}" --techniques shadow-rays --frames 1 -o "$work/ref" >/dev/null
python3 -c "
import json; r = json.load(open('$work/ref/report.json'))['reference']
print(f\"reference: {r.get('paths', 0)} paths, {r['frame_ms'] / 1000:.1f} s, own noise mean dE {r.get('noise_de_mean', float('nan')):.3f}\")"
echo "| technique | mean dE | p99 dE | frame ms (median of $runs) |"
echo "|---|---|---|---|"
row() {  # label, technique, params...
  local label=$1 technique=$2
  shift 2
  for i in $(seq "$runs"); do
    "$bin" compare "$work/scene.json" --size "${size}x${size}" --reference-image "$work/ref/reference.exr" \
      --techniques "$technique" --frames 1 "$@" -o "$work/run$i" >/dev/null
    cat "$work/run$i/report.json"; echo
  done | python3 -c "
import json, sys, statistics
text = sys.stdin.read()
rows, dec, i = [], json.JSONDecoder(), 0
while True:
    while i < len(text) and text[i].isspace(): i += 1
    if i >= len(text): break
    obj, i = dec.raw_decode(text, i)
    rows.append(obj['techniques'][0])
print(f\"| $label | {rows[0]['mean_de']:.3f} | {rows[0]['p99_de']:.2f} | {statistics.median(r['frame_ms'] for r in rows):.0f} |\")"
}
for n in 1 4 16 64; do row "shadow-rays light_samples=$n" shadow-rays --param "shadow-rays.light_samples=$n"; done
for spp in 16 64 256; do
  row "pathtrace single, $spp spp" pathtrace --param pathtrace.spp=$spp --param pathtrace.min_spp=$spp \
    --param pathtrace.target_error=0 --param pathtrace.progress=false
done
echo "# $(( $(date +%s) - start )) s in all"
