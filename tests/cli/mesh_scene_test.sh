#!/usr/bin/env bash
# penumbra render with meshes in the scene, end to end: the warning when the
# technique does not draw them, and the errors for bad mesh keys and files.
# Usage: mesh_scene_test.sh PENUMBRA_BINARY WORK_DIR
set -u
bin=$(realpath "$1")  # absolute: one check runs in another folder
work=$2
rm -rf "$work" && mkdir -p "$work"
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# run SCENE ARGS...: renders SCENE to $work/out.png; sets rc, out (stdout) and err (stderr).
run() {
  local scene=$1
  shift
  rm -f "$work/out.png"
  out=$("$bin" render "$scene" -o "$work/out.png" "$@" 2>"$work/stderr")
  rc=$?
  err=$(cat "$work/stderr")
}

# scene MESHES_JSON: a scene with an empty 8^3 volume and these meshes.
scene() {
  printf '{"volume": {"builtin": "empty", "size": [8, 8, 8]}, "render": {"width": 16, "height": 16}, "meshes": %s}' "$1"
}

scene '[{"builtin": "sphere", "scale": 3}]' > "$work/sphere.json"

# A technique that does not draw meshes: a warning on stderr (not stdout) naming those that do, and the image anyway.
run "$work/sphere.json" --technique phong --size 16x16
[ "$rc" -eq 0 ] || fail "phong exited $rc: $err"
grep -qF "warning: phong does not draw the scene's 1 mesh(es); convolution, pathtrace, shadow-rays do" <<<"$err" ||
  fail "no mesh warning on stderr: $err"
grep -qi "warning" <<<"$out" && fail "the warning went to stdout: $out"
[ -s "$work/out.png" ] || fail "phong wrote no image"

# convolution and shadow-rays draw them: no warning.
for technique in convolution shadow-rays; do
  run "$work/sphere.json" --technique $technique --size 16x16
  [ "$rc" -eq 0 ] || fail "$technique exited $rc: $err"
  grep -qi "warning" <<<"$err" && fail "$technique warned: $err"
  [ -s "$work/out.png" ] || fail "$technique wrote no image"
  head -c 8 "$work/out.png" | od -An -c | grep -q "P   N   G" || fail "$technique's out.png is not a PNG"
done

# No meshes, no warning.
printf '{"volume": {"builtin": "spheres", "size": [8, 8, 8]}}' > "$work/no_meshes.json"
run "$work/no_meshes.json" --technique phong --size 16x16
[ "$rc" -eq 0 ] || fail "a scene without meshes exited $rc: $err"
grep -qi "warning" <<<"$err" && fail "a scene without meshes warned: $err"

# A mesh file is found beside the scene, whatever the working directory.
mkdir -p "$work/scene_dir" "$work/elsewhere"
printf 'v 0 0 0\nv 3 0 0\nv 0 3 0\nv 0 0 3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$work/scene_dir/tet.obj"
scene '[{"file": "tet.obj"}]' > "$work/scene_dir/tet.json"
out=$(cd "$work/elsewhere" && "$bin" render ../scene_dir/tet.json -o out.png --technique convolution 2>&1)
rc=$?
[ "$rc" -eq 0 ] || fail "a mesh file beside the scene: exited $rc: $out"
[ -s "$work/elsewhere/out.png" ] || fail "a mesh file beside the scene: no image"

# expect_error MESHES_JSON NEEDLE: exit code 2 and NEEDLE in the message, no image.
expect_error() {
  scene "$1" > "$work/bad.json"
  run "$work/bad.json" --technique convolution
  [ "$rc" -eq 2 ] || fail "meshes $1 exited $rc, expected 2: $out$err"
  grep -qF -- "$2" <<<"$err" || fail "meshes $1: the message lacks '$2': $err"
  [ -e "$work/out.png" ] && fail "meshes $1: an image was written"
}

expect_error '[{"builtin": "sphere", "colour": [1, 0, 0]}]' "meshes[0].colour"
expect_error '[{"builtin": "sphere"}, {"builtin": "teapot"}]' "meshes[1].builtin"
expect_error '[{"builtin": "sphere", "file": "tet.obj"}]' "meshes[0]"
expect_error '[{"builtin": "sphere", "scale": 0}]' "meshes[0].scale"
expect_error '[{"builtin": "sphere", "material": {"detail": {"type": "marble"}}}]' "meshes[0].material.detail.type"
expect_error '{"builtin": "sphere"}' "meshes"
expect_error '[{"file": "no_such_mesh.obj"}]' "no_such_mesh.obj"
expect_error '[{"builtin": "sphere", "material": {"detail": {"type": "texture", "texture": "no_such_texture.nrrd"}}}]' \
  "no_such_texture.nrrd"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' > "$work/broken.obj"
expect_error '[{"file": "broken.obj"}]' "broken.obj"
expect_error '[{"file": "broken.obj"}]' "OBJ line 4"

# --frames: the animated detail (a "time" key) advances by --time-step per
# frame, frame i in out-000i.png; the first frame is the scene as written.
scene '[{"builtin": "sphere", "scale": 3, "material": {"detail": {"type": "fbm", "frequency": 4, "time": 0.5},
        "transfer_function": {"points": [[-1, 1, 1, 1, 0.0], [1, 1, 1, 1, 0.9]]}}}]' > "$work/animated.json"
rm -f "$work"/seq-*.png
out=$("$bin" render "$work/animated.json" -o "$work/seq.png" --technique convolution --frames 3 --time-step 0.4 2>"$work/stderr")
rc=$?
[ "$rc" -eq 0 ] || fail "--frames 3 exited $rc: $(cat "$work/stderr")"
for i in 0 1 2; do [ -s "$work/seq-000$i.png" ] || fail "--frames 3 wrote no seq-000$i.png"; done
[ "$(grep -c 'seq-000' <<<"$out")" -eq 3 ] || fail "--frames 3 did not print the three paths: $out"
cmp -s "$work/seq-0000.png" "$work/seq-0001.png" && fail "frames 0 and 1 are the same image: the detail did not move"
run "$work/animated.json" --technique convolution
cmp -s "$work/out.png" "$work/seq-0000.png" || fail "frame 0 differs from a plain render of the scene"
# Errors: no animated detail to advance, a frame count out of range.
run "$work/sphere.json" --technique convolution --frames 2
[ "$rc" -eq 2 ] && grep -qF -- "--frames" <<<"$err" || fail "--frames without animated detail: rc $rc: $err"
run "$work/animated.json" --technique convolution --frames 0
[ "$rc" -eq 2 ] && grep -qF -- "--frames" <<<"$err" || fail "--frames 0: rc $rc: $err"

if [ "$failures" -gt 0 ]; then
  echo "$failures mesh scene check(s) failed"
  exit 1
fi
echo "all mesh scene checks passed"
