#!/usr/bin/env bash
# convolution (Patel et al. 2013) in the shape of the paper's Fig. 11 list:
# median frame ms of `penumbra bench` for 1 and 2 lights and the kernels
# ellipse-2, ellipse-3, poisson-8, poisson-16 and gaussian (19 x 19), on two
# scenes: the engine CT (scenes/engine-directional.json, slab_distance 1
# voxels) and a mesh with procedural detail (scenes/knot-fbm.json: a
# ridged-multifractal torus knot, 24576 triangles, over a floor; slab
# distance 0.5). Every light is a Gaussian light of variance SIGMA2 (tan^2
# units, default 0.01: 5.7 degrees) per axis on the virtual light plane (a
# zero-variance light makes every kernel a single tap). The slab count each
# frame used is printed (bench's passes_per_frame).
#
# The paper times 768^2 on a GPU; this CPU implementation convolves every
# texel of every light buffer per slab, so a frame costs
# slabs x pixels x lights x taps bilinear reads: at 768^2 the 19 x 19 Gaussian
# takes minutes per frame on 2 cores (GAUSSIAN=0 skips it).
#
# Usage: scripts/bench-convolution.sh [FRAMES]      (default 1 timed frame)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   SIZE=768                    image side
#   SCENES="engine knot"        which scenes
#   GAUSSIAN=1                  include the 19 x 19 Gaussian kernel
#   KERNELS="gaussian:19"       instead: this list of kernel:samples
#   SIGMA2=0.01                 light variance per axis
#   OUT=dir                     raw results (default build/bench-convolution)
# The engine scene needs ../shared/data/engine_256x256x128_uint8.nhdr.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
out=${OUT:-$root/build/bench-convolution}
frames=${1:-1}
size=${SIZE:-768}
scenes=${SCENES:-engine knot}
gaussian=${GAUSSIAN:-1}
sigma2=${SIGMA2:-0.01}
mkdir -p "$out"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$out/load.txt"

# The scene with a second, bluish light from the upper left.
add_light() {
  python3 - "$1" "$2" <<'PY'
import json, pathlib, sys
src = pathlib.Path(sys.argv[1])
s = json.load(open(src))
if "file" in s["volume"]:
    s["volume"]["file"] = str(src.parent / s["volume"]["file"])
s["lights"].append({"type": "directional", "direction": [-0.2, 0.8, -0.9], "color": [0.6, 0.7, 1.0], "intensity": 0.8})
json.dump(s, open(sys.argv[2], "w"))
PY
}

kernels="ellipse:2 ellipse:3 poisson:8 poisson:16"
[ "$gaussian" = 1 ] && kernels="$kernels gaussian:19"
kernels=${KERNELS:-$kernels}
for name in $scenes; do
  case $name in
    engine) one=$root/scenes/engine-directional.json slab=1.0 ;;
    knot) one=$root/scenes/knot-fbm.json slab=0.5 ;;
    *) echo "unknown scene $name (engine, knot)" >&2; exit 2 ;;
  esac
  two=$out/$name-two-lights.json
  add_light "$one" "$two"
  echo
  echo "$name, ${size}^2, slab_distance $slab"
  echo "| kernel | 1 light ms | 2 lights ms | slabs |"
  echo "|---|---|---|---|"
  for k in $kernels; do
    kname=${k%%:*} samples=${k##*:}
    row="| $kname-$samples"
    slabs=""
    for scene in "$one" "$two"; do
      line=$("$bin" bench "$scene" --technique convolution --size "${size}x${size}" --frames "$frames" \
               --param slab_distance="$slab" --param kernel="$kname" --param kernel_samples="$samples" \
               --param light_sigma_x2="$sigma2" --param light_sigma_y2="$sigma2" | tail -1)
      echo "$line" >> "$out/results.jsonl"
      ms=$(python3 -c 'import json,sys; print("%.0f" % json.loads(sys.argv[1])["frame_ms_median"])' "$line")
      slabs=$(python3 -c 'import json,sys; print(json.loads(sys.argv[1])["passes_per_frame"])' "$line")
      row="$row | $ms"
    done
    echo "$row | $slabs |"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$out/load.txt"
