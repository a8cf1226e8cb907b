#!/usr/bin/env bash
# ipsvi's aux memory and frame time against the camera's field of view
# (issue 21): the scene's camera zoomed toward its target at FOVS degrees,
# `penumbra bench` (prepare + render per frame, orbiting 2 degrees) for ipsvi
# and shadow-rays. Prints one markdown table.
#
# Usage: scripts/bench-ipsvi-fov.sh SCENE.json [SIZE]   (default 128)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   FOVS="40 32 16 9 6 3"       fields of view
#   FRAMES=3                    frames for the median
#   TECHNIQUES="ipsvi shadow-rays"
#   ERROR=1                     add ipsvi's mean / p99 dE against exact shadow
#                               rays (penumbra compare, one frame) per fov
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
scene=$1
size=${2:-128}
fovs=${FOVS:-40 32 16 9 6 3}
frames=${FRAMES:-3}
techniques=${TECHNIQUES:-ipsvi shadow-rays}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene_dir=$(cd "$(dirname "$scene")" && pwd)
echo "machine: $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
error=${ERROR:-0}
echo "| fov | $(for t in $techniques; do printf '%s ms | %s MB | ' "$t" "$t"; done)$([ "$error" = 1 ] && printf 'ipsvi dE mean / p99 |')"
echo "|---$(for t in $techniques; do printf '|---|---'; done)$([ "$error" = 1 ] && printf '|---')|"
for fov in $fovs; do
  zoomed=$tmp/fov-$fov.json
  python3 - "$scene" "$fov" "$scene_dir" > "$zoomed" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1]))
s["camera"]["fov_deg"] = float(sys.argv[2])
v = s.get("volume", {})
if "file" in v and not os.path.isabs(v["file"]):  # relative to the scene's folder
    v["file"] = os.path.normpath(os.path.join(sys.argv[3], v["file"]))
print(json.dumps(s))
PY
  row="| $fov |"
  for t in $techniques; do
    extra=()
    [ "$t" = shadow-rays ] && extra=(--param shadow_cache=false)  # exact shadow rays
    line=$("$bin" bench "$zoomed" --technique "$t" "${extra[@]}" --size "${size}x${size}" --frames "$frames" | tail -n 1)
    ms=$(echo "$line" | python3 -c 'import json,sys; r=json.load(sys.stdin); print("%.1f | %.2f" % (r["frame_ms_median"], r["aux_bytes"] / 1e6))')
    row="$row $ms |"
  done
  if [ "$error" = 1 ]; then
    "$bin" compare "$zoomed" --techniques ipsvi --reference shadow-rays --param shadow-rays.shadow_cache=false \
      --size "${size}x${size}" --frames 1 -o "$tmp/compare-$fov" > /dev/null 2>&1
    de=$(python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); t=[x for x in r["techniques"] if x["technique"]=="ipsvi"][0]; print("%.2f / %.2f" % (t["mean_de"], t["p99_de"]))' "$tmp/compare-$fov/report.json")
    row="$row $de |"
  fi
  echo "$row"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
