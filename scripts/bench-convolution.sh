#!/usr/bin/env bash
# convolution (Patel et al. 2013) in the shape of the paper's Fig. 11 list:
# median frame ms of `penumbra bench` for 1 and 2 lights and the kernels
# ellipse-2, ellipse-3, poisson-8, poisson-16 and gaussian (19 x 19), on the
# engine CT with about 500 slabs (slab_distance 0.75 voxels), every light a
# Gaussian light of variance SIGMA2 (tan^2 units, default 0.01: 5.7 degrees)
# per axis on the virtual light plane (a zero-variance light makes every
# kernel a single tap).
#
# The paper times 768^2 on a GPU; this CPU implementation convolves every
# texel of every light buffer per slab, so a frame costs
# slabs x pixels x lights x taps bilinear reads: at 768^2 the 19 x 19 Gaussian
# takes minutes per frame on 2 cores. Default size 256; SIZE=768 for the
# paper's size (GAUSSIAN=0 skips the Gaussian there).
#
# Usage: scripts/bench-convolution.sh [FRAMES]      (default 1 timed frame)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   SIZE=256                    image side
#   SLAB=0.75                   slab distance in voxels
#   GAUSSIAN=1                  include the 19 x 19 Gaussian kernel
#   SIGMA2=0.01                 light variance per axis
#   OUT=dir                     raw results (default build/bench-convolution)
# Needs ../shared/data/engine_256x256x128_uint8.nhdr (scenes/engine-directional.json).
# Mesh scenes with procedural detail are not implemented yet.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
out=${OUT:-$root/build/bench-convolution}
frames=${1:-1}
size=${SIZE:-256}
slab=${SLAB:-0.75}
gaussian=${GAUSSIAN:-1}
sigma2=${SIGMA2:-0.01}
mkdir -p "$out"
echo "machine: $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$out/load.txt"

one=$root/scenes/engine-directional.json
two=$out/engine-two-lights.json
# The engine scene with a second, bluish light from the upper left.
python3 - "$one" "$two" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["volume"]["file"] = str(__import__("pathlib").Path(sys.argv[1]).parent / s["volume"]["file"])
s["lights"].append({"type": "directional", "direction": [-0.2, 0.8, -0.9], "color": [0.6, 0.7, 1.0], "intensity": 0.8})
json.dump(s, open(sys.argv[2], "w"))
PY

kernels="ellipse:2 ellipse:3 poisson:8 poisson:16"
[ "$gaussian" = 1 ] && kernels="$kernels gaussian:19"
echo "| kernel | 1 light ms | 2 lights ms | slabs |"
echo "|---|---|---|---|"
for k in $kernels; do
  name=${k%%:*} samples=${k##*:}
  row="| $name-$samples"
  for scene in "$one" "$two"; do
    line=$("$bin" bench "$scene" --technique convolution --size "${size}x${size}" --frames "$frames" \
             --param slab_distance="$slab" --param kernel="$name" --param kernel_samples="$samples" \
             --param light_sigma_x2="$sigma2" --param light_sigma_y2="$sigma2" | tail -1)
    echo "$line" >> "$out/results.jsonl"
    ms=$(python3 -c 'import json,sys; print("%.0f" % json.loads(sys.argv[1])["frame_ms_median"])' "$line")
    row="$row | $ms"
  done
  echo "$row | ~500 |"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$out/load.txt"
