#!/usr/bin/env bash
# Checks that the SIMD units (cmake/PenumbraSimd.cmake) define only symbols
# whose names belong to their instruction set: a function in a target
# namespace (penumbra::N_AVX2, penumbra::N_AVX3), an instantiation on a
# SimdTarget, or a shared inline function that scripts/simd-compile.sh
# renamed for the target (suffix .penumbra_Avx2 / .penumbra_Avx3). Any other
# global symbol is a copy of shared code compiled with AVX2 or AVX-512 flags,
# which the linker could keep for every caller (packet_render.h). And every
# COMDAT group is named for the target (scripts/simd-compile.sh).
# Usage: check-simd-symbols.sh OBJECT...
set -euo pipefail
status=0
for object in "$@"; do
  # nm and readelf run in process substitutions, whose failures set -e does
  # not see: a path that is not an object must fail here, not pass empty.
  if ! nm "$object" > /dev/null 2>&1; then
    echo "check-simd-symbols: not an object file: $object" >&2
    status=1
    continue
  fi
  while IFS= read -r line; do
    echo "check-simd-symbols: $(basename "$object"): not target-specific: $line" >&2
    status=1
  done < <(nm -C --defined-only "$object" |
             awk '$2 ~ /^[A-Zuvw]$/ && $2 != "U"' |
             cut -d' ' -f3- |
             grep -v -E 'N_AVX2::|N_AVX3::|\(penumbra::SimdTarget\)[12]|\.penumbra_Avx[23]\]?$' || true)
  # A COMDAT group under a shared name (a constructor's C5 group, say) is
  # dropped by the linker when another unit has one of that name, taking the
  # renamed code inside it along and leaving calls to it at address 0.
  while IFS= read -r group; do
    echo "check-simd-symbols: $(basename "$object"): COMDAT group not target-specific: $group" >&2
    status=1
  done < <(readelf -gW "$object" | sed -n 's/^COMDAT group section.*\[\(.*\)\] contains.*/\1/p' |
             grep -v -E 'N_AVX2|N_AVX3|SimdTargetE[12]|\.penumbra_Avx[23]$' || true)
done
[ "$status" -eq 0 ] && echo "check-simd-symbols: $# objects, every global symbol target-specific"
exit "$status"
