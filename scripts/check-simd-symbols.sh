#!/usr/bin/env bash
# Checks that the SIMD units (cmake/PenumbraSimd.cmake) define only symbols
# whose names belong to their instruction set: a function in a target
# namespace (penumbra::N_AVX2, penumbra::N_AVX3), an instantiation on a
# SimdTarget, or a shared inline function that scripts/simd-compile.sh
# renamed for the target (suffix .penumbra_Avx2 / .penumbra_Avx3). Any other
# global symbol is a copy of shared code compiled with AVX2 or AVX-512 flags,
# which the linker could keep for every caller (packet_render.h).
# Usage: check-simd-symbols.sh OBJECT...
set -euo pipefail
status=0
for object in "$@"; do
  while IFS= read -r line; do
    echo "check-simd-symbols: $(basename "$object"): not target-specific: $line" >&2
    status=1
  done < <(nm -C --defined-only "$object" |
             awk '$2 ~ /^[A-Zuvw]$/ && $2 != "U"' |
             cut -d' ' -f3- |
             grep -v -E 'N_AVX2::|N_AVX3::|\(penumbra::SimdTarget\)[12]|\.penumbra_Avx[23]\]?$' || true)
done
[ "$status" -eq 0 ] && echo "check-simd-symbols: $# objects, every global symbol target-specific"
exit "$status"
