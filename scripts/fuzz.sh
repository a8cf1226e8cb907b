#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [HARNESS ...]: builds the libFuzzer targets of
# tests/fuzz with clang, ASan and UBSan in build-fuzz/ (PENUMBRA_FUZZ=ON),
# makes the seed corpora from ../shared/data and scenes/, and runs each target
# (default: all of them, one after the other) for SECONDS (default 600) on one
# worker. The corpus grows in build-fuzz/corpus/<harness>; findings (crashes,
# sanitizer reports, hangs over 10 s, allocations over 2 GB) land in
# build-fuzz/findings/<harness>/ and are listed at the end. A run goes on after
# a finding (-fork=1 with -ignore_*), so one bug does not hide the next.
# To keep a finding: minimize it (fuzz_<harness> -minimize_crash=1 -runs=10000
# FILE), fix the bug, and copy the input into tests/fuzz/regressions/<harness>/,
# where `make test` replays it without clang. docs/RELIABILITY.md has more.
set -euo pipefail

seconds="${1:-600}"
[ $# -gt 0 ] && shift
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${FUZZ_BUILD:-$root/build-fuzz}"
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(nrrd metaimage nifti vti dat scene obj ply preset server)

"$root/scripts/install-deps.sh" --clang
cxx=""
for c in clang++-14 clang++; do command -v "$c" > /dev/null && { cxx="$c"; break; }; done
cc="${cxx/++/}"
probe='extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }'
if [ -z "$cxx" ] || ! echo "$probe" | "$cxx" -x c++ -fsanitize=fuzzer - -o /dev/null 2> /dev/null; then
  echo "fuzz.sh: needs clang with libFuzzer: scripts/install-deps.sh --clang" >&2
  exit 1
fi

CC="$cc" CXX="$cxx" cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only" -DPENUMBRA_FUZZ=ON \
  -DPENUMBRA_NATIVE=OFF -DPENUMBRA_ENABLE_CUDA=OFF > /dev/null
targets=(fuzz_make_seeds)
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
cmake --build "$build" --target "${targets[@]}"

rm -rf "$build/seeds"
"$build/tests/fuzz/fuzz_make_seeds" "$build/seeds" "$root/../shared/data" "$root/scenes"

summary=()
for h in "${harnesses[@]}"; do
  mkdir -p "$build/corpus/$h" "$build/findings/$h" "$build/seeds/$h"
  log="$build/findings/$h.log"
  echo "fuzz.sh: fuzz_$h for ${seconds}s (log: $log)" >&2
  # Single worker; -timeout and -malloc_limit_mb are the issue's thresholds
  # for a hang and a huge allocation.
  "$build/tests/fuzz/fuzz_$h" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -malloc_limit_mb=2048 \
    -artifact_prefix="$build/findings/$h/" "$build/corpus/$h" "$build/seeds/$h" > "$log" 2>&1 || true
  # The fork driver's last status line: "#EXECS: cov: .. corp: .. exec/s .. oom/timeout/crash: A/B/C time: .."
  last="$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)"
  execs="$(echo "$last" | sed -nE 's/^#([0-9]+):.*/\1/p')"
  otc="$(echo "$last" | sed -nE 's/.*oom\/timeout\/crash: ([0-9]+\/[0-9]+\/[0-9]+).*/\1/p')"
  found="$(find "$build/findings/$h" -type f | wc -l)"
  summary+=("fuzz_$h: ${execs:-?} executions in ${seconds}s, oom/timeout/crash ${otc:-?}, $found file(s) in findings/$h")
  # Children that crashed leave their fixture folders behind.
  for d in /dev/shm/penumbra_fuzz_*; do
    [ -d "$d" ] && [ ! -d "/proc/${d##*_}" ] && rm -rf "$d"
  done
done
printf '%s\n' "${summary[@]}"
