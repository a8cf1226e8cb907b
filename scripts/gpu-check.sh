#!/usr/bin/env bash
# The CUDA backend's check on a machine with an NVIDIA GPU, in one command
# that fits in 8 minutes: the GPU tests (each technique with a CUDA path
# against the CPU on three scenes, light move / TF change against a fresh
# render, no uploads for an unchanged scene, the device memory error), then a
# bench of every technique with a CUDA path at 1024x1024 on a 512^3 volume
# (pathtrace at 8 paths per pixel), printed as one table.
#
#   scripts/gpu-check.sh            # configures and builds here (Debian with penumbra's dependencies)
#   scripts/gpu-check.sh BUNDLE     # runs a folder made by scripts/gpu-bundle.sh (no libraries needed)
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [ $# -ge 1 ]; then
  bundle="$(cd "$1" && pwd)"
  bin="$bundle/bin"
  scenes="$bundle/repo/scenes"
  export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  export PENUMBRA_TEST_SOURCE_DIR="$bundle/repo" PENUMBRA_TEST_SHARED_DATA_DIR="$bundle/shared/data"
else
  root="$(cd "$here/.." && pwd)"
  build="${BUILD:-$root/build-gpu}"
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPENUMBRA_ENABLE_CUDA=ON \
    -DPENUMBRA_BUILD_TESTS=ON -DPENUMBRA_BUILD_PYTHON=OFF > /dev/null || exit 1
  cmake --build "$build" --target penumbra penumbra_tests || exit 1
  bin="$build"
  scenes="$root/scenes"
fi

echo "== device"
command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader
echo "== GPU tests"
timeout 300 "$bin/penumbra_tests" --gtest_filter='Device*:CudaDevice*' --gtest_brief=1
tests=$?

echo "== bench: 1024x1024, 512^3 marschner-lobb (scenes/gpu-bench-512.json), 10 frames each"
techniques=(emission-absorption phong shadow-rays shadow-map deep-shadow-map cssm filtered-sat sat-ao cone-shadows
            ambient-scattering occlusion-map)
args=()
for t in "${techniques[@]}"; do args+=(--technique "$t"); done
json=$(timeout 240 "$bin/penumbra" --device cuda bench "$scenes/gpu-bench-512.json" "${args[@]}" --frames 10)
bench=$?
# occlusion-map's DVR mode (the row after its iso mode's).
json+=$'\n'$(timeout 60 "$bin/penumbra" --device cuda bench "$scenes/gpu-bench-512.json" --technique occlusion-map \
  --param occlusion-map.mode=dvr --frames 10)
[ $? -eq 0 ] || bench=1
# pathtrace (single scattering, 8 paths per pixel): its samples/s are volume lookups/s.
json+=$'\n'$(timeout 90 "$bin/penumbra" --device cuda bench "$scenes/gpu-bench-512.json" --technique pathtrace \
  --param pathtrace.spp=8 --param pathtrace.min_spp=8 --param pathtrace.progress=false --frames 3)
[ $? -eq 0 ] || bench=1
field() { sed -n "s/.*\"$1\": \"\{0,1\}\([^\",}]*\).*/\1/p" <<< "$2"; }
printf '%-20s %-6s %10s %8s %14s %15s %10s %14s\n' technique device frame_ms fps tf_change_ms light_move_ms aux_MB samples/s
while IFS= read -r line; do
  [ -z "$line" ] && continue
  ms=$(field frame_ms_median "$line")
  printf '%-20s %-6s %10s %8.1f %14s %15s %10.1f %14s\n' "$(field technique "$line")" "$(field device "$line")" "$ms" \
    "$(awk -v m="$ms" 'BEGIN { print (m > 0 ? 1000 / m : 0) }')" "$(field tf_change_ms "$line")" \
    "$(field light_move_ms "$line")" "$(awk -v b="$(field aux_bytes "$line")" 'BEGIN { print b / 1048576 }')" \
    "$(field samples_per_s "$line")"
done <<< "$json"
echo "== tests: $([ $tests -eq 0 ] && echo passed || echo FAILED), bench: $([ $bench -eq 0 ] && echo ran || echo FAILED)"
[ $tests -eq 0 ] && [ $bench -eq 0 ]
