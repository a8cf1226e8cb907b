#!/usr/bin/env bash
# ipsvi and half-angle in the shape of Sundén et al. 2011, Table 1 and Fig. 11:
# frames per second (1000 / the median frame time of `penumbra bench`, whose
# camera orbits 2 degrees per frame as the paper rotates about the up vector)
# at 64^2 .. 1024^2 image sizes, for line widths 1, 2 and 4, with and without
# piecewise integration, on the engine CT and on the 256^3 synthetic volume;
# then, at the same sizes, ipsvi with its ERT extension, half-angle slicing and
# shadow-rays (the exact single-scattering ray caster) for comparison.
#
# Usage: scripts/bench-ipsvi.sh [FRAMES [SIZE...]]   (default: 3 frames; 64 128 256 512 1024)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   OUT=dir                     raw results (default build/bench-ipsvi)
# Needs ../shared/data/engine_256x256x128_uint8.nhdr (scenes/engine.json) and
# build/peer/synth256.nrrd (scenes/peer_synthetic.json, made by
# scripts/bench-vs-vtk.sh); a missing volume is skipped.
# Prints the markdown tables of docs/PERFORMANCE.md ("ipsvi, half-angle").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
out=${OUT:-$root/build/bench-ipsvi}
frames=${1:-3}
shift || true
sizes=${*:-64 128 256 512 1024}
mkdir -p "$out"
results=$out/results.jsonl
: > "$results"
echo "machine: $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$out/load.txt"

run() {  # data size label bench-arguments...
  local data=$1 size=$2 label=$3
  shift 3
  local line
  line=$("$bin" bench "$@" --size "${size}x${size}" --frames "$frames" | tail -n 1)
  printf '{"data": "%s", "size": %s, "label": "%s", "result": %s}\n' "$data" "$size" "$label" "$line" >> "$results"
  echo "$data ${size}^2 $label: $(echo "$line" | sed 's/.*"frame_ms_median": \([0-9.]*\).*/\1/') ms" >&2
}

for data in engine synthetic; do
  case $data in
    engine) scene=$root/scenes/engine.json volume=$root/../shared/data/engine_256x256x128_uint8.nhdr ;;
    synthetic) scene=$root/scenes/peer_synthetic.json volume=$root/build/peer/synth256.nrrd ;;
  esac
  if [ ! -f "$volume" ]; then
    echo "skipping $data: $volume is missing" >&2
    continue
  fi
  for size in $sizes; do
    for pi in true false; do
      for lw in 1 2 4; do
        run "$data" "$size" "pi=$pi lw=$lw" "$scene" --technique ipsvi --param "line_width=$lw" \
          --param "piecewise_integration=$pi"
      done
    done
    run "$data" "$size" "ert" "$scene" --technique ipsvi --param early_termination=true
    run "$data" "$size" "half-angle" "$scene" --technique half-angle
    run "$data" "$size" "shadow-rays" "$scene" --technique shadow-rays --param shadow_cache=false
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$out/load.txt"

python3 - "$results" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
fps = {(r["data"], r["size"], r["label"]): 1000.0 / r["result"]["frame_ms_median"] for r in rows}
memory = {(r["data"], r["label"]): r["result"]["aux_bytes"] for r in rows}
labels = [f"pi={p} lw={w}" for p in ("true", "false") for w in (1, 2, 4)] + ["ert", "half-angle", "shadow-rays"]
heads = ["PI LW1", "PI LW2", "PI LW4", "no PI LW1", "no PI LW2", "no PI LW4", "PI LW1 + ERT", "half-angle", "shadow-rays"]
for data in ("engine", "synthetic"):
    sizes = sorted({s for d, s, _ in fps if d == data})
    if not sizes:
        continue
    print(f"\n{data}: frames per second\n")
    print("| image | " + " | ".join(heads) + " |")
    print("|---" * (len(heads) + 1) + "|")
    for s in sizes:
        cells = [f"{fps[(data, s, l)]:.2f}" if (data, s, l) in fps else "" for l in labels]
        print(f"| {s}² | " + " | ".join(cells) + " |")
PY
