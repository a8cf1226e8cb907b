#!/usr/bin/env bash
# Compiler launcher of the SIMD units (cmake/PenumbraSimd.cmake): compiles,
# then renames each weak function the unit defines under a name other units
# share (an inline function of a shared header, kept out of line here and
# compiled with this unit's AVX2 or AVX-512 flags) to a name of its own
# target, so the linker can never pick this copy for code that runs on a
# CPU without the instruction set. It is what Highway's per-target
# namespaces do for code written inside them, applied to the shared scalar
# code the lane kernels call. Usage: simd-compile.sh COMPILER ARGS...
set -euo pipefail
"$@"
out="" target=""
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case "${args[i]}" in
    -o) out="${args[i + 1]}" ;;
    -DPENUMBRA_SIMD_TARGET=*) target="${args[i]#-DPENUMBRA_SIMD_TARGET=}" ;;
  esac
done
if [ -z "$out" ] || [ -z "$target" ]; then exit 0; fi
map="$out.renames"
# The same symbols in the same (symbol table) order, mangled and demangled.
paste -d '\t' <(nm -p --defined-only "$out" | awk '{print $2 " " $3}') \
              <(nm -p -C --defined-only "$out" | cut -d' ' -f3-) |
  awk -F'\t' -v suffix=".penumbra_${target}" '
    { split($1, kind_name, " "); kind = kind_name[1]; name = kind_name[2] }
    kind == "W" && $2 !~ /N_AVX2::|N_AVX3::|\(penumbra::SimdTarget\)[12]/ { print name " " name suffix }' > "$map"
# A constructor's or destructor's COMDAT group is named by a local C5/D5
# symbol, not by the function: left as is, the linker would keep another
# unit's group of that name and drop this one, and the calls here to the
# renamed function would resolve to address 0. So every group holding a
# renamed function's code is renamed with it.
if [ -s "$map" ]; then
  readelf -gW "$out" | awk -v suffix=".penumbra_${target}" '
    NR == FNR { renamed[$1] = 1; next }
    /^COMDAT group section/ { match($0, /\[[^]]*\] contains/); group = substr($0, RSTART + 1, RLENGTH - 11) }
    $NF ~ /^\.text\./ { name = substr($NF, 7); if ((name in renamed) && !(group in renamed) && !(group in done)) {
        print group " " group suffix; done[group] = 1 } }' "$map" - >> "$map"
  objcopy --redefine-syms="$map" "$out"
fi
rm -f "$map"
