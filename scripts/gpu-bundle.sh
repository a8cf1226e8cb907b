#!/usr/bin/env bash
# Builds penumbra with the CUDA backend, portable (no -march=native: the SIMD
# units still pick AVX2 or AVX-512 at run time), and bundles into gpu-bundle/
# (git-ignored, under 64 MiB) what scripts/gpu-check.sh needs on a GPU machine
# that has the CUDA driver but none of penumbra's libraries: the CLI and the
# test binary (stripped), the shared libraries they load (ldd; not glibc's,
# whose newer copy that machine has, nor the driver's libcuda), the scenes and
# the two CT volumes the GPU tests use, and gpu-check.sh itself.
#
#   scripts/gpu-bundle.sh              # then copy gpu-bundle/ over and run
#   gpu-bundle/gpu-check.sh gpu-bundle
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${BUILD:-$root/build-gpu}"
out="$root/gpu-bundle"
data="$root/../shared/data"

"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPENUMBRA_ENABLE_CUDA=ON -DPENUMBRA_NATIVE=OFF \
  -DPENUMBRA_BUILD_TESTS=ON -DPENUMBRA_BUILD_PYTHON=OFF > /dev/null
cmake --build "$build" -j "$(nproc)" --target penumbra penumbra_tests

rm -rf "$out"
mkdir -p "$out/bin" "$out/lib" "$out/repo/scenes" "$out/shared/data"
for exe in penumbra penumbra_tests; do
  cp "$build/$exe" "$out/bin/"
  strip "$out/bin/$exe"
done
# Shared libraries, but not the C library's own (the GPU machine's glibc is
# newer and must stay its own) nor the driver's.
ldd "$build/penumbra" "$build/penumbra_tests" | awk '/=> \// {print $3}' | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|ld-linux*|libcuda.so.*) ;;
    *) cp -L "$lib" "$out/lib/" ;;
  esac
done
cp "$root"/scenes/{engine-point,head-point,gpu-bench-512}.json "$out/repo/scenes/"
for volume in engine_256x256x128_uint8 ct_head_cranium_256x256x108_int16; do
  cp "$data/$volume".* "$out/shared/data/"
done
cp "$root/scripts/gpu-check.sh" "$out/"
size=$(du -sm "$out" | cut -f1)
echo "gpu-bundle: $out, ${size} MiB"
if [ "$size" -ge 64 ]; then
  echo "gpu-bundle: over 64 MiB" >&2
  exit 1
fi
