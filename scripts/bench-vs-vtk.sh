#!/usr/bin/env bash
# penumbra vs VTK 9.1 (the peer in ../shared/peers) on the same 256^3 synthetic
# volume, image (512x512), transfer function, camera and step (1 voxel), in one
# session so the ratio is fair on a noisy machine. Also times the engine CT.
# Needs: make build, and the peer's packages (see ../shared/peers/README.md).
# Usage: scripts/bench-vs-vtk.sh [RUNS]   (default 3 runs of everything)
#   PENUMBRA_BASE_BIN=/path/penumbra  also an older build, and this build with --simd off, in each run
#   QUICK=1                           emission-absorption and phong on the peer scene only
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
bin=${PENUMBRA_BIN:-build/penumbra}  # another build: PENUMBRA_BIN=build-x/penumbra
peer=../shared/peers/vtk_dvr_bench.py
mkdir -p build/peer
[ -f build/peer/synth256.nrrd ] || /usr/bin/python3 "$peer" --dump-nrrd build/peer/synth256.nrrd --configs cpu0 --frames 1 > /dev/null
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
for run in $(seq 1 "$runs"); do
  echo "# run $run"
  /usr/bin/python3 "$peer" --configs cpu0,cpu1 --frames 10 --outdir build/peer | grep -v '^#'
  peer_techniques=(--technique emission-absorption --technique phong)
  [ "${QUICK:-0}" = 1 ] || peer_techniques+=(--technique shadow-rays)
  if [ -n "${PENUMBRA_BASE_BIN:-}" ]; then
    "$PENUMBRA_BASE_BIN" bench scenes/peer_synthetic.json "${peer_techniques[@]}" --frames 10 | sed 's/^/before /'
    "$bin" --simd off bench scenes/peer_synthetic.json "${peer_techniques[@]}" --frames 10 | sed 's/^/simd-off /'
  fi
  "$bin" bench scenes/peer_synthetic.json "${peer_techniques[@]}" --frames 10
  if [ "${QUICK:-0}" != 1 ] && [ -f ../shared/data/engine_256x256x128_uint8.nhdr ]; then
    "$bin" bench scenes/engine.json --technique emission-absorption --technique phong --technique shadow-rays --frames 10 --param shadow-rays.shadow_cache=false
  fi
done
