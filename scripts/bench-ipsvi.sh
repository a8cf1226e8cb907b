#!/usr/bin/env bash
# ipsvi and half-angle in the shape of Sundén et al. 2011, Table 1: frames per
# second (1000 / the median frame time of `penumbra bench`, whose camera orbits
# 2 degrees per frame as the paper rotates about the up vector) at 64^2 ..
# 1024^2, for line widths 1, 2 and 4, with and without piecewise integration,
# on the engine CT and on the 256^3 synthetic volume, and half-angle slicing at
# the same sizes. At 256^2 and 512^2 also ipsvi with its ERT extension (5.1)
# and, at 256^2, shadow-rays (the exact single-scattering ray caster).
#
# Budget: about 3 minutes on a quiet 2-core machine with the defaults. The
# largest sizes (BIG, default 1024) run only PI LW1 and half-angle, which is
# what dominates the time; BIG_ALL=1 runs the whole matrix there too (about 5
# more minutes on 2 cores).
#
# Usage: scripts/bench-ipsvi.sh [FRAMES [SIZE...]]   (default: 1 frame after a warm-up; 64 128 256 512)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   OUT=dir                     raw results (default build/bench-ipsvi)
#   BIG="1024"                  sizes with the reduced set ("" to skip)
# Needs ../shared/data/engine_256x256x128_uint8.nhdr (scenes/engine.json) and
# build/peer/synth256.nrrd (scenes/peer_synthetic.json, made by
# scripts/bench-vs-vtk.sh); a missing volume is skipped.
# Prints the markdown tables of docs/PERFORMANCE.md ("ipsvi, half-angle").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
out=${OUT:-$root/build/bench-ipsvi}
frames=${1:-1}
shift || true
sizes=${*:-64 128 256 512}
big=${BIG-1024}
mkdir -p "$out"
results=$out/results.jsonl
: > "$results"
start=$(date +%s)
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
  for size in $sizes $big; do
    full=1
    case " $big " in *" $size "*) [ "${BIG_ALL:-0}" = 1 ] || full=0 ;; esac
    for pi in true false; do
      for lw in 1 2 4; do
        if [ $full = 1 ] || { [ $pi = true ] && [ $lw = 1 ]; }; then
          run "$data" "$size" "pi=$pi lw=$lw" "$scene" --technique ipsvi --param "line_width=$lw" \
            --param "piecewise_integration=$pi"
        fi
      done
    done
    if [ $full = 1 ] && { [ "$size" = 256 ] || [ "$size" = 512 ]; }; then
      run "$data" "$size" "ert" "$scene" --technique ipsvi --param early_termination=true
    fi
    run "$data" "$size" "half-angle" "$scene" --technique half-angle
    if [ "$size" = 256 ]; then
      run "$data" "$size" "shadow-rays" "$scene" --technique shadow-rays --param shadow_cache=false
    fi
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg); $(( $(date +%s) - start )) s" | tee -a "$out/load.txt"

python3 - "$results" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
res = {(r["data"], r["size"], r["label"]): r["result"] for r in rows}
labels = [f"pi={p} lw={w}" for p in ("true", "false") for w in (1, 2, 4)] + ["ert", "half-angle", "shadow-rays"]
heads = ["PI LW1", "PI LW2", "PI LW4", "no PI LW1", "no PI LW2", "no PI LW4", "PI LW1 + ERT", "half-angle", "shadow-rays"]
for data in ("engine", "synthetic"):
    sizes = sorted({s for d, s, _ in res if d == data})
    if not sizes:
        continue
    print(f"\n{data}: frames per second\n")
    print("| image | " + " | ".join(heads) + " |")
    print("|---" * (len(heads) + 1) + "|")
    for s in sizes:
        cells = [f"{1000.0 / res[(data, s, l)]['frame_ms_median']:.2f}" if (data, s, l) in res else "" for l in labels]
        print(f"| {s}² | " + " | ".join(cells) + " |")
    print(f"\n{data}: aux memory (MB) and viewing-ray samples per frame (M)\n")
    print("| image | ipsvi MB | ipsvi+ERT MB | half-angle MB | ipsvi samples | ipsvi+ERT samples |")
    print("|---|---|---|---|---|---|")
    for s in sizes:
        def get(label, key, scale):
            r = res.get((data, s, label))
            return f"{r[key] / scale:.2f}" if r else ""
        print(f"| {s}² | {get('pi=true lw=1', 'aux_bytes', 1e6)} | {get('ert', 'aux_bytes', 1e6)} | "
              f"{get('half-angle', 'aux_bytes', 1e6)} | {get('pi=true lw=1', 'samples_per_frame', 1e6)} | "
              f"{get('ert', 'samples_per_frame', 1e6)} |")
PY
