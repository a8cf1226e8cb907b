#!/usr/bin/env bash
# End-to-end checks of the penumbra command line: outputs, exit codes and
# error messages. Usage: cli_test.sh PENUMBRA_BINARY SOURCE_DIR WORK_DIR
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

expect 0 "render" -- "$bin" --help
expect 0 "shadow_density_scale" -- "$bin" techniques
expect 0 "emission-absorption" -- "$bin" techniques
expect 0 "scattering_albedo" -- "$bin" techniques   # ambient-scattering

# Rendering a scene file to PNG and EXR.
expect 0 "spheres.png" -- "$bin" render "$src/scenes/spheres.json" -o "$work/spheres.png" --size 32x24
head -c 8 "$work/spheres.png" | od -An -c | grep -q "P   N   G" || fail "spheres.png is not a PNG"
expect 0 "" -- "$bin" render "$src/scenes/spheres.json" -o "$work/spheres.exr" --size 16x16 --technique phong
[ -s "$work/spheres.exr" ] || fail "no EXR written"
expect 0 "demo.png" -- "$bin" render --demo -o "$work/demo.png" --size 48x48

# Bad input: exit code 2 and one line naming what is wrong.
expect 2 "teapot" -- "$bin" render "$src/scenes/spheres.json" -o "$work/x.png" --technique teapot
expect 2 "filter_voxels" -- "$bin" render "$src/scenes/spheres.json" -o "$work/x.png" --param filter_voxels=3
expect 2 "shadow_density_scale" -- "$bin" render "$src/scenes/spheres.json" -o "$work/x.png" --param shadow_density_scale=-1
expect 2 "--size" -- "$bin" render "$src/scenes/spheres.json" -o "$work/x.png" --size 0x10
expect 2 "no_such_scene.json" -- "$bin" render "$work/no_such_scene.json" -o "$work/x.png"
expect 2 ".png or .exr" -- "$bin" render "$src/scenes/spheres.json" -o "$work/x.jpg"
printf '{"volume": {"builtin": "spheres"}, "lights": [{"type": "directional", "colour": [1, 0, 0]}]}' > "$work/bad_key.json"
expect 2 "lights[0].colour" -- "$bin" render "$work/bad_key.json" -o "$work/x.png"
printf '{"volume": {"builtin": "spheres"}, "render": {"width": "wide"}}' > "$work/bad_type.json"
expect 2 "render.width" -- "$bin" render "$work/bad_type.json" -o "$work/x.png"
printf '{"volume": {"file": "missing.nrrd"}}' > "$work/missing_volume.json"
expect 2 "missing.nrrd" -- "$bin" render "$work/missing_volume.json" -o "$work/x.png"
printf '{"volume": ' > "$work/truncated.json"
expect 2 "JSON" -- "$bin" render "$work/truncated.json" -o "$work/x.png"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\nencoding: raw\n\nabc' > "$work/truncated.nrrd"
expect 2 "truncated.nrrd" -- "$bin" info "$work/truncated.nrrd"
expect 2 "" -- "$bin" render
expect 2 "" -- "$bin" frobnicate

# info on a volume we write ourselves (raw NRRD, 4x3x2 uint8 values 0..23).
{ printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: 1 2 3\nencoding: raw\n\n'; \
  for i in $(seq 0 23); do printf "\\$(printf %o "$i")"; done; } > "$work/tiny.nrrd"
expect 0 "4 x 3 x 2" -- "$bin" info "$work/tiny.nrrd"
expect 0 "value range 0 .. 23" -- "$bin" info "$work/tiny.nrrd"
expect 0 "spacing     1 2 3" -- "$bin" info "$work/tiny.nrrd"

# bench: one JSON line per technique with the documented keys.
out=$("$bin" bench "$src/scenes/spheres.json" --technique emission-absorption --technique shadow-rays --frames 2 --size 16x16 2>&1)
[ "$(grep -c '^{' <<<"$out")" -eq 2 ] || fail "bench printed $(grep -c '^{' <<<"$out") JSON lines, expected 2: $out"
for key in technique volume dims image tf_change_ms light_move_ms frame_ms_median frame_ms_min aux_bytes threads; do
  grep -q "\"$key\": " <<<"$out" || fail "bench output lacks \"$key\": $out"
done
[ "$(grep -c '"passes_per_frame": 0,' <<<"$out")" -eq 2 ] || fail "ray casters report no sweep passes: $out"
# lane_utilisation is a share of the SIMD lanes: between 0 and 1.
grep -Eq '"lane_utilisation": (0\.[0-9]+|1\.000)\}' <<<"$out" || fail "bench lacks a lane_utilisation in [0, 1]: $out"
# convolution reports its slab count, about depth / slab distance.
out=$("$bin" bench "$src/scenes/spheres.json" --technique convolution --frames 1 --size 16x16 --param slab_distance=2 2>&1)
slabs=$(sed -n 's/.*"passes_per_frame": \([0-9]*\).*/\1/p' <<<"$out")
[ -n "$slabs" ] && [ "$slabs" -gt 10 ] && [ "$slabs" -lt 200 ] || fail "convolution bench reports $slabs slabs: $out"
expect 2 "teapot" -- "$bin" bench "$src/scenes/spheres.json" --technique teapot --frames 1

# plot: a PNG from a series,x,y table; a malformed table names the file and line.
printf 'series,x,y\n# light size\nshadow-rays,0,0.2\nshadow-rays,8,0.9\nfiltered-sat,0,1.5\nfiltered-sat,8,2.5\n' > "$work/plot.csv"
expect 0 "" -- "$bin" plot "$work/plot.csv" -o "$work/plot.png" --title "error" --x-label "deg" --y-label "dE"
head -c 8 "$work/plot.png" | od -An -c | grep -q "P   N   G" || fail "plot.png is not a PNG"
printf 'series,x,y\nshadow-rays,0,zero\n' > "$work/bad.csv"
expect 2 "bad.csv: line 2: column y" -- "$bin" plot "$work/bad.csv" -o "$work/bad.png"
printf 'name,value\n' > "$work/header.csv"
expect 2 "header.csv" -- "$bin" plot "$work/header.csv" -o "$work/bad.png"
expect 2 "missing.csv" -- "$bin" plot "$work/missing.csv" -o "$work/bad.png"
expect 2 "--size" -- "$bin" plot "$work/plot.csv" -o "$work/bad.png" --size 0x0

if [ "$failures" -gt 0 ]; then
  echo "$failures CLI check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
