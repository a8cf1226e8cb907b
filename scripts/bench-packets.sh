#!/usr/bin/env bash
# The packet path against the scalar path and (optionally) an older build, on
# the engine CT at 512x512 with every technique that renders through the
# shared loop, in one session so the ratios are fair on a noisy machine
# (docs/PERFORMANCE.md, "CPU packets"). Prints one JSON line per run, binary
# and technique, then a table of medians.
# Usage: scripts/bench-packets.sh [RUNS] [THREADS]   (default 3 runs, all cores)
#   PENUMBRA_BIN=build-x/penumbra     the build to measure (default build/penumbra)
#   PENUMBRA_BASE_BIN=/path/penumbra  an older build to compare with (its "simd" is reported as "before")
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
threads=${2:-0}
bin=${PENUMBRA_BIN:-build/penumbra}
base=${PENUMBRA_BASE_BIN:-}
scene=${SCENE:-scenes/engine.json}
size=${SIZE:-512x512}
techniques=(emission-absorption phong shadow-rays filtered-sat sat-ao cone-shadows shadow-map deep-shadow-map cssm
            ambient-scattering occlusion-map)
args=()
for t in "${techniques[@]}"; do args+=(--technique "$t"); done
out=$(mktemp)
trap 'rm -f "$out" "$out.one"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')," \
     "load $(cut -d' ' -f1-3 /proc/loadavg), $scene $size, threads $threads"
for run in $(seq 1 "$runs"); do
  if [ -n "$base" ]; then
    # An older build may not know every technique: it runs those it knows.
    for t in "${techniques[@]}"; do
      if ! "$base" --threads "$threads" bench "$scene" --technique "$t" --size "$size" --frames 5 > "$out.one" 2>&1; then
        echo "# before: $t skipped ($(head -c 200 "$out.one"))"
        continue
      fi
      sed 's/^{/{"build": "before", /' "$out.one" | tee -a "$out"
    done
  fi
  for simd in off auto; do
    "$bin" --threads "$threads" --simd "$simd" bench "$scene" "${args[@]}" --size "$size" --frames 5 |
      sed "s/^{/{\"build\": \"simd=$simd\", /" | tee -a "$out"
  done
done
python3 - "$out" <<'EOF'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.startswith("{")]
builds = list(dict.fromkeys(r["build"] for r in rows))
techs = list(dict.fromkeys(r["technique"] for r in rows))
med = {(b, t): statistics.median(r["frame_ms_median"] for r in rows if r["build"] == b and r["technique"] == t)
       for b in builds for t in techs if any(r["build"] == b and r["technique"] == t for r in rows)}
cell = lambda b, t: f"{med[(b, t)]:.1f}" if (b, t) in med else "-"
print("| technique | " + " | ".join(f"{b} ms" for b in builds) + " | x phong (auto) | speed-up vs " + builds[0] + " |")
print("|---" * (len(builds) + 3) + "|")
for t in techs:
    cells = " | ".join(cell(b, t) for b in builds)
    speedup = f"{med[(builds[0], t)] / med[('simd=auto', t)]:.2f}" if (builds[0], t) in med else "-"
    print(f"| {t} | {cells} | {med[('simd=auto', t)] / med[('simd=auto', 'phong')]:.2f} | {speedup} |")
EOF
