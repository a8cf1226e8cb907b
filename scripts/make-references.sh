#!/usr/bin/env bash
# Renders the pathtrace reference images in scenes/reference/ (256 x 256,
# linear float EXR) from the reference scenes scenes/<name>.json, whose
# render.params ask pathtrace for single scattering with adaptive stopping at
# a lightness standard error of 0.4 CIE L* per pixel. Each render goes
# through `penumbra compare` against shadow-rays, so the summary beside each
# EXR (<name>.json: paths, the reference's own noise in CIEDE2000, and
# shadow-rays' distance to it) shows the reference converged to the model.
#
# Usage: scripts/make-references.sh [NAME...]      (default: all six)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   THREADS=N                   worker threads (default: all cores)
#   MODE=multiple               multiple scattering instead (the physically
#                               based target), written as <name>-multiple.*
# Takes minutes per scene on a few cores; the EXRs are committed, so this is
# only needed after a change to the optical model.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
threads=${THREADS:-0}
mode=${MODE:-single}
case $mode in
  single) suffix= ;;
  multiple) suffix=-multiple ;;
  *) echo "MODE must be single or multiple" >&2; exit 2 ;;
esac
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(engine-directional engine-point head-directional head-point shell-directional
                                  shell-point)
out=$root/scenes/reference
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in "${names[@]}"; do
  scene=$root/scenes/$name.json
  [ -f "$scene" ] || { echo "no scene $scene" >&2; exit 2; }
  start=$(date +%s)
  "$bin" --threads "$threads" compare "$scene" --techniques shadow-rays --frames 1 --param "pathtrace.mode=$mode" \
    -o "$work/$name" >/dev/null
  seconds=$(( $(date +%s) - start ))
  cp "$work/$name/reference.exr" "$out/$name$suffix.exr"
  python3 - "$work/$name/report.json" "$out/$name$suffix.json" "$seconds" "$name" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
ref, sr = report["reference"], report["techniques"][0]
summary = {
    "scene": "scenes/" + sys.argv[4] + ".json",
    "image": report["image"],
    "params": ref["params"],
    "paths": ref["paths"],
    "noise_de_mean": ref["noise_de_mean"],
    "noise_de_median": ref["noise_de_median"],
    "noise_de_p99": ref["noise_de_p99"],
    "shadow_rays_mean_de": sr["mean_de"],
    "shadow_rays_p99_de": sr["p99_de"],
    "render_seconds": int(sys.argv[3]),
}
json.dump(summary, open(sys.argv[2], "w"), indent=2)
print("{}: {:.0f} paths/pixel, noise dE mean {:.2f} median {:.2f} p99 {:.2f}; shadow-rays mean dE {:.2f}; {} s".format(
    sys.argv[2].split("/")[-1][:-5], ref["paths"] / (report["image"][0] * report["image"][1]), ref["noise_de_mean"],
    ref["noise_de_median"], ref["noise_de_p99"], sr["mean_de"], sys.argv[3]))
PY
done
ls -l "$out"
