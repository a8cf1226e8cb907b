#!/usr/bin/env bash
# scripts/sanitize.sh: the unit test suites under AddressSanitizer and
# UndefinedBehaviorSanitizer (`make sanitize`; CI runs it after `make test`).
# Builds penumbra_tests, penumbra_server_tests and penumbra_fuzz_regressions
# with -DPENUMBRA_SANITIZE=address,undefined in build-sanitize/ (clang 14, as
# the fuzz build, -O1; UBSan includes float-cast-overflow, so NaN or 1e30
# cast to an int is a report), runs each binary in two shards at
# once, and fails on any failing test or sanitizer report: the build makes
# every report fatal (-fno-sanitize-recover), and the logs are searched for
# reports as well. The end-to-end tests (CLI scripts, web viewer, load test)
# are not run here: they measure whole programs, not the library under test.
# The SIMD packet units are left out (PENUMBRA_SIMD=OFF): ASan does not
# instrument Highway's gathers and masked loads, so they would add compile
# and run time (the packet-vs-scalar tests are the suite's slowest) without
# memory checks, and CI must stay under 30 minutes on 2 cores. The kernels
# they instantiate are the same lane-generic code that runs here at one lane,
# and make test checks the packet instances against it (Lanes, PacketPath).
#
# SANITIZERS (default address,undefined) and SANITIZE_BINARIES (default the
# three above) narrow it: CI on a slow machine runs ASan alone on the fuzz
# regressions and the server tests (.ci/run, docs/RELIABILITY.md "CI time").
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(realpath -m "${SANITIZE_BUILD:-$root/build-sanitize}")"
jobs="${JOBS:-$(nproc)}"
sanitizers="${SANITIZERS:-address,undefined}"
binaries=(${SANITIZE_BINARIES:-penumbra_tests apps/server/penumbra_server_tests tests/fuzz/penumbra_fuzz_regressions})
targets=()
for binary in "${binaries[@]}"; do targets+=("$(basename "$binary")"); done

start=$(date +%s)
# SANITIZE_RUN_ONLY=1: run the binaries of an existing sanitizer build (for
# example build-fuzz/ with tests on, whose objects carry ASan and UBSan too).
if [ "${SANITIZE_RUN_ONLY:-0}" != 1 ]; then
  "$root/scripts/install-deps.sh" --clang
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DPENUMBRA_SANITIZE="$sanitizers" -DPENUMBRA_BUILD_TESTS=ON -DPENUMBRA_SIMD=OFF -DPENUMBRA_ENABLE_CUDA=OFF > /dev/null
  cmake --build "$build" -j "$jobs" --target "${targets[@]}"
fi
built=$(date +%s)

export ASAN_OPTIONS="abort_on_error=1:halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
logs="$build/sanitize-logs"
rm -rf "$logs"
mkdir -p "$logs"
shards=2
pids=()
names=()
for binary in "${binaries[@]}"; do
  for ((s = 0; s < shards; ++s)); do
    name="$(basename "$binary").$s"
    (cd "$build" && GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$s "./$binary" --gtest_brief=1 \
       > "$logs/$name.log" 2>&1) &
    pids+=($!)
    names+=("$name")
  done
  # One binary's shards at a time: two processes on two cores.
  status=0
  for i in "${!pids[@]}"; do
    if ! wait "${pids[$i]}"; then
      echo "sanitize: ${names[$i]} failed; its log:" >&2
      tail -n 60 "$logs/${names[$i]}.log" >&2
      status=1
    fi
  done
  pids=()
  names=()
  [ $status -eq 0 ] || exit 1
done
if grep -l -E "ERROR: (Address|Leak)Sanitizer|runtime error:" "$logs"/*.log; then
  echo "sanitize: sanitizer reports in the logs above" >&2
  exit 1
fi
finished=$(date +%s)
tests=$(grep -h -oE '\[==========\] [0-9]+ tests? from' "$logs"/*.log | awk '{s += $2} END {print s}')
echo "sanitize: ${tests:-0} tests passed under $sanitizers, no reports (build $((built - start)) s, run $((finished - built)) s)"
