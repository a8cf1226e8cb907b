#!/usr/bin/env bash
# Speed of the pathtrace reference: paths per second and volume lookups per
# second (delta/ratio tracking and next-event estimation together) for single
# and multiple scattering on three reference scenes at 256 x 256, 16 paths
# per pixel, with shadow-rays on the same scenes for scale. Prints one
# markdown row per case with the median of RUNS runs of `penumbra bench`.
#
# Usage: scripts/bench-pathtrace.sh [RUNS]     (default 3)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
runs=${1:-3}
spp=16
echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| scene | technique | frame ms (median of $runs) | paths/s | volume lookups/s |"
echo "|---|---|---|---|---|"
for scene in shell-directional engine-directional head-point; do
  for technique in pathtrace:single pathtrace:multiple shadow-rays; do
    name=${technique%%:*}
    args=(--technique "$name" --size 256x256 --frames 1)
    [ "$name" = pathtrace ] && args+=(--param "mode=${technique#*:}" --param spp=$spp --param min_spp=$spp
                                      --param target_error=0 --param progress=false)
    for _ in $(seq "$runs"); do "$bin" bench "$root/scenes/$scene.json" "${args[@]}"; done |
      python3 -c "
import json, sys, statistics
rows = [json.loads(line) for line in sys.stdin if line.startswith('{')]
ms = statistics.median(r['frame_ms_median'] for r in rows)
lookups = statistics.median(r['samples_per_s'] for r in rows)
paths = 256 * 256 * $spp / (ms * 1e-3) if '$name' == 'pathtrace' else float('nan')
paths = '-' if paths != paths else '{:.3g}'.format(paths)
print('| $scene | $technique | {:.0f} | {} | {:.3g} |'.format(ms, paths, lookups))"
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
