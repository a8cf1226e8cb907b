#!/usr/bin/env bash
# End-to-end checks of `penumbra compare`: the files it writes, the keys of
# report.json, and clear errors for unknown techniques and parameters.
# Usage: compare_test.sh PENUMBRA_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1
src=$2
work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect CODE NEEDLE -- command...: exit code CODE and NEEDLE in stdout+stderr.
expect() {
  local code=$1 needle=$2
  shift 3
  local out rc
  out=$("$@" 2>&1)
  rc=$?
  [ "$rc" -eq "$code" ] || fail "'$*' exited $rc, expected $code: $out"
  if [ -n "$needle" ] && ! grep -qF -- "$needle" <<<"$out"; then fail "'$*' output lacks '$needle': $out"; fi
}

scene=$src/scenes/shell-directional.json
small=(--size 24x24 --frames 1 --param pathtrace.spp=8 --param pathtrace.min_spp=8 --param pathtrace.target_error=0)

# Two techniques against a small pathtrace reference.
expect 0 "report.md" -- "$bin" compare "$scene" --techniques shadow-rays,phong "${small[@]}" -o "$work/out"
for f in reference.png reference.exr reference-stderr.exr reference-noise.png grid.png report.json report.md \
         shadow-rays.png shadow-rays.exr shadow-rays-de.png shadow-rays-luminance.png \
         phong.png phong.exr phong-de.png; do
  [ -s "$work/out/$f" ] || fail "compare did not write $f"
done
head -c 8 "$work/out/grid.png" | od -An -c | grep -q "P   N   G" || fail "grid.png is not a PNG"
for key in '"reference"' '"noise_de_mean"' '"technique": "shadow-rays"' '"technique": "phong"' '"rmse"' '"psnr"' \
           '"ssim"' '"mean_de"' '"p99_de"' '"tf_change_ms"' '"light_move_ms"' '"frame_ms"' '"aux_bytes"'; do
  grep -qF "$key" "$work/out/report.json" || fail "report.json lacks $key"
done
python3 -c "import json, sys; json.load(open(sys.argv[1]))" "$work/out/report.json" 2>/dev/null ||
  { command -v python3 >/dev/null && fail "report.json is not valid JSON"; }
grep -qF "| shadow-rays |" "$work/out/report.md" || fail "report.md lacks the shadow-rays row"
# No progress bar when stderr is not a terminal: no carriage returns.
out=$("$bin" compare "$scene" --techniques emission-absorption "${small[@]}" -o "$work/quiet" 2>&1)
grep -q $'\r' <<<"$out" && fail "progress bar drawn although stderr is not a terminal"

# Against a stored reference image (the one just written), and the same
# technique as reference: identical images give dE 0 and PSNR null (infinite).
expect 0 "mean dE 0.00" -- "$bin" compare "$scene" --techniques shadow-rays --size 24x24 --frames 1 \
  --reference-image "$work/out/shadow-rays.exr" -o "$work/stored"
grep -qF '"psnr": null' "$work/stored/report.json" || fail "identical images should give psnr null"
expect 2 "--reference-image" -- "$bin" compare "$scene" --techniques phong --size 16x16 \
  --reference-image "$work/out/reference.exr" -o "$work/x"

# Every technique on a reference scene whose render.params are pathtrace's
# (occlusion-map's "mode" refuses pathtrace's value and must skip it).
expect 0 "report.md" -- "$bin" compare "$src/scenes/shell-point.json" --techniques all --size 16x16 --frames 1 \
  --param resolution=256 --param pathtrace.spp=4 --param pathtrace.min_spp=4 --param pathtrace.target_error=0 \
  -o "$work/all"
grep -qF "| occlusion-map |" "$work/all/report.md" || fail "compare --techniques all lacks occlusion-map"
# And on an area-light reference scene (issue 18): every technique follows the sphere light's size.
expect 0 "report.md" -- "$bin" compare "$src/scenes/shell-sphere.json" --techniques all --size 16x16 --frames 1 \
  --param resolution=256 --param pathtrace.spp=4 --param pathtrace.min_spp=4 --param pathtrace.target_error=0 \
  -o "$work/all-sphere"
grep -qF "| cssm |" "$work/all-sphere/report.md" || fail "compare --techniques all on shell-sphere lacks cssm"
# Per-technique objects in render.params, and a prefix that names no technique.
sed 's/"params": {[^}]*}/"params": {"pathtrace": {"mode": "single", "spp": 4, "min_spp": 4, "target_error": 0}, "shadow-rays": {"shadow_cache": true}}/' \
  "$src/scenes/shell-point.json" > "$work/per-technique.json"
expect 0 "report.md" -- "$bin" compare "$work/per-technique.json" --techniques shadow-rays,occlusion-map --size 16x16 \
  --frames 1 -o "$work/per"
grep -qF '"shadow_cache": true' "$work/per/report.json" || fail "the per-technique shadow_cache did not reach shadow-rays"
sed 's/"params": {[^}]*}/"params": {"teapot": {"spout": 1}}/' "$src/scenes/shell-point.json" > "$work/bad-prefix.json"
expect 2 "render.params.teapot" -- "$bin" compare "$work/bad-prefix.json" --techniques phong --size 16x16 -o "$work/x"
sed 's/"mode": "single"/"mode": "triple"/' "$src/scenes/shell-point.json" > "$work/bad-mode.json"
expect 2 "technique 'pathtrace' refuses it" -- "$bin" render "$work/bad-mode.json" --size 16x16 -o "$work/x.png"

# A mesh scene (issue 23): convolution and shadow-rays against the path tracer, all three drawing the meshes,
# so no warning; shadow-rays (the hard-shadow reference) within about its reference's noise (measured mean dE
# 0.35 against noise 0.44 at 24x24, 256 paths), convolution within its slab error (measured 2.6), and a
# technique that does not draw the meshes warns and misses them (measured 11.7).
sed 's/"ambient": 0.1/"ambient": 0.0/' "$src/scenes/mesh-sphere.json" > "$work/mesh-sphere.json"  # pathtrace has no ambient
mesh_small=(--size 24x24 --frames 1 --param pathtrace.spp=256 --param pathtrace.min_spp=256 --param pathtrace.target_error=0)
out=$("$bin" compare "$work/mesh-sphere.json" --techniques convolution,shadow-rays "${mesh_small[@]}" -o "$work/mesh" 2>&1)
rc=$?
[ "$rc" -eq 0 ] || fail "compare on a mesh scene exited $rc: $out"
grep -qi "warning" <<<"$out" && fail "compare warned about techniques that draw meshes: $out"
for row in "| convolution |" "| shadow-rays |"; do
  grep -qF "$row" "$work/mesh/report.md" || fail "the mesh scene's report.md lacks '$row'"
done
python3 - "$work/mesh/report.json" <<'PY' || fail "the mesh scene's report.json: $(cat "$work/mesh/report.json")"
import json, sys
report = json.load(open(sys.argv[1]))
de = {t["technique"]: t["mean_de"] for t in report["techniques"]}
assert report["reference"]["technique"] == "pathtrace"
assert de["shadow-rays"] < 1.0, de
assert de["convolution"] < 5.0, de
PY
out=$("$bin" compare "$work/mesh-sphere.json" --techniques phong "${mesh_small[@]}" -o "$work/mesh-phong" 2>&1)
grep -qF "warning: phong does not draw the scene's 1 mesh(es); convolution, pathtrace, shadow-rays do" <<<"$out" ||
  fail "compare did not warn that phong does not draw the meshes: $out"
python3 -c "import json, sys; assert json.load(open(sys.argv[1]))['techniques'][0]['mean_de'] > 5.0" \
  "$work/mesh-phong/report.json" || fail "phong's image matched a mesh scene it does not draw"

# Bad input: exit code 2 and one line naming what is wrong.
expect 2 "unknown technique 'teapot'" -- "$bin" compare "$scene" --techniques shadow-rays,teapot -o "$work/x"
expect 2 "known: " -- "$bin" compare "$scene" --techniques teapot -o "$work/x"
expect 2 "unknown technique 'kettle'" -- "$bin" compare "$scene" --techniques phong --reference kettle -o "$work/x"
expect 2 "filter_voxels" -- "$bin" compare "$scene" --techniques phong --param filter_voxels=3 -o "$work/x"
expect 2 "cssm-like" -- "$bin" compare "$scene" --techniques phong --param cssm-like.k=3 -o "$work/x"
expect 2 "spp" -- "$bin" compare "$scene" --techniques phong --param pathtrace.spp=0 -o "$work/x"
expect 2 "" -- "$bin" compare "$scene" --techniques phong
[ -e "$work/x" ] && fail "a failed compare left an output folder"

if [ "$failures" -gt 0 ]; then
  echo "$failures compare check(s) failed"
  exit 1
fi
echo "all compare checks passed"
