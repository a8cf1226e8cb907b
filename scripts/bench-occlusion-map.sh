#!/usr/bin/env bash
# occlusion-map (Penner & Mitchell 2008) in the shape of the paper's Tables 1
# and 2, plus the 2- versus 4-moment accuracy measurement:
#   1. preprocessing: the moment pyramid's build for the engine CT, the head CT
#      and a 512^3 uint8 synthetic (2 and 4 moments), its memory, and the cost
#      of an iso-value change and a TF change (prepare() with rebuilds() before
#      and after: no rebuild);
#   2. frames at 512 x 512 (`penumbra bench`, median of FRAMES frames) on the
#      engine CT and the head CT: Phong (no AO, no shadows), AO, hard shadows
#      (HS), soft shadows (SS), and AO + SS together; and DVR mode (Fig. 11)
#      with AO and soft shadows;
#   3. with `accuracy`: the occluded-fraction error of the 2- and 4-moment
#      bounds against brute force over whole volumes (about a minute more).
# The measurements of 1 and 3 are disabled tests in penumbra_tests
# (src/penumbra/techniques/occlusion_map/*_test.cpp).
#
# Usage: scripts/bench-occlusion-map.sh [RUNS] [accuracy]   (RUNS default 3: medians over runs)
#   BUILD=dir       the build folder with penumbra and penumbra_tests (default build)
#   OUT=dir         scenes and raw results (default $BUILD/bench-occlusion-map)
#   FRAMES=n        frames per `penumbra bench` (default 3)
#   SIMD=mode       `--simd` of the frames (default auto; off: the scalar path)
#   FRAMES_ONLY=1   skip the preprocessing measurements
# Needs ../shared/data (engine, head). Takes about 1-2 minutes on a quiet 2-core
# machine (the 512^3 synthetic's build is most of part 1).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
bin=$build/penumbra
tests=$build/penumbra_tests
out=${OUT:-$build/bench-occlusion-map}
runs=${1:-3}
frames=${FRAMES:-3}
mkdir -p "$out"
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"

if [ "${FRAMES_ONLY:-0}" != 1 ]; then
  echo "## preprocessing and iso-value change (medians of $runs)"
  OCCLUSION_MAP_RUNS=$runs "$tests" --gtest_also_run_disabled_tests \
    --gtest_filter='OcclusionMapBench.DISABLED_*' | grep '\[occlusion-map bench\]' | sed 's/^\[occlusion-map bench\] //'
fi

# The engine and head scenes of scenes/ (directional light, floor plane) with
# an ambient term for the AO to act on and the iso-values of the docs' images.
python3 - "$root" "$out" <<'PY'
import json, os, sys
root, out = sys.argv[1], sys.argv[2]
for name, source in (("engine", "engine-directional.json"), ("head", "head-directional.json")):
    scene = json.load(open(os.path.join(root, "scenes", source)))
    scene["volume"]["file"] = os.path.normpath(os.path.join(root, "scenes", scene["volume"]["file"]))
    scene["material"] = {"shading": "phong", "ambient": 0.3}
    scene["render"] = {"width": 512, "height": 512, "step": 0.5, "technique": "occlusion-map", "params": {}}
    json.dump(scene, open(os.path.join(out, name + ".json"), "w"), indent=1)
PY

echo "## frames at 512x512 (penumbra bench --simd ${SIMD:-auto}, median of $frames frames)"
echo "| data set | iso_value | Phong ms | AO ms | HS ms | SS ms | AO+SS ms | DVR AO+SS ms |"
echo "|---|---|---|---|---|---|---|---|"
for item in engine:0.5 head:0.47; do
  name=${item%%:*}
  iso=${item##*:}
  row="| $name | $iso |"
  for mode in "ambient_occlusion=false shadows=none" "ambient_occlusion=true shadows=none" \
              "ambient_occlusion=false shadows=hard" "ambient_occlusion=false shadows=soft" \
              "ambient_occlusion=true shadows=soft" "mode=dvr ambient_occlusion=true shadows=soft"; do
    args=(--param iso_value=$iso)
    for p in $mode; do args+=(--param "$p"); done
    ms=$("$bin" --simd "${SIMD:-auto}" bench "$out/$name.json" --technique occlusion-map "${args[@]}" --frames "$frames" --size 512x512 2>/dev/null |
         python3 -c 'import json,sys; print("%.0f" % json.loads(sys.stdin.read().strip().splitlines()[-1])["frame_ms_median"])')
    row="$row $ms |"
  done
  echo "$row"
done

if [ "${2:-}" = accuracy ]; then
  echo "## occluded-fraction error, whole volumes"
  "$tests" --gtest_also_run_disabled_tests --gtest_filter='OcclusionMapAccuracy.DISABLED_*' |
    grep '\[occlusion-map accuracy\]' | sed 's/^\[occlusion-map accuracy\] //'
fi
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
