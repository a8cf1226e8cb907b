#!/usr/bin/env bash
# The soft-shadow comparison of docs/comparison-report.md (issue 18): every
# technique at its defaults, which follow the scene light's size, against the
# stored path-traced references of the engine and head CT under a
# directional light and 2- and 8-degree distant lights (angle_deg, the
# cone's half-angle) and of the shell under a point light and a sphere light
# of radius 20. shadow-rays runs twice: at its default (one ray to the
# light's centre: hard shadows) and with SAMPLES area-light rays (the
# deterministic soft-shadow reference); the shadow maps run twice as well,
# at their default and with their PCSS option (soft=auto).
#
# Usage: scripts/soft-shadow-table.sh [OUT_DIR]     (default out/soft-shadows)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   SAMPLES=N                   shadow-rays' light_samples row (default 16)
#   ONLY=a,b                    render these techniques again (their rows
#                               replace the stored ones; after a change to them)
# Writes OUT_DIR/<scene>/ (compare's output), OUT_DIR/soft-shadows.md (the
# table), OUT_DIR/soft-shadow-<volume>.csv and .png (mean dE against the
# light's size, one line per shadowing DVR technique, drawn by `penumbra plot`). A scene
# whose report.json exists is not rendered again.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
samples=${SAMPLES:-16}
out=${1:-$root/out/soft-shadows}
mkdir -p "$out"
scenes=(engine-directional engine-distant-2 engine-distant-8 head-directional head-distant-2 head-distant-8
        shell-point shell-sphere)
for name in "${scenes[@]}"; do
  ref=$root/scenes/reference/$name.exr
  [ -f "$ref" ] || { echo "no reference $ref (scripts/make-references.sh $name)" >&2; exit 2; }
  if [ ! -f "$out/$name/report.json" ]; then
    echo "compare $name" >&2
    "$bin" compare "$root/scenes/$name.json" --techniques all --reference-image "$ref" --frames 1 -o "$out/$name" \
      >/dev/null
  fi
  if [ -n "${ONLY:-}" ]; then
    "$bin" compare "$root/scenes/$name.json" --techniques "$ONLY" --reference-image "$ref" --frames 1 \
      -o "$out/$name-update" >/dev/null
  fi
  if [ ! -f "$out/$name-samples/report.json" ]; then
    "$bin" compare "$root/scenes/$name.json" --techniques shadow-rays,shadow-map,deep-shadow-map,cssm \
      --param "shadow-rays.light_samples=$samples" --param soft=auto \
      --reference-image "$ref" --frames 1 -o "$out/$name-samples" >/dev/null
  fi
done
python3 - "$out" "$samples" <<'PY'
import json, os, sys
out, samples = sys.argv[1], sys.argv[2]
# (volume, light size label, x for the plot, scene)
rows = [("engine", "0", 0, "engine-directional"), ("engine", "2 deg", 2, "engine-distant-2"),
        ("engine", "8 deg", 8, "engine-distant-8"), ("head", "0", 0, "head-directional"),
        ("head", "2 deg", 2, "head-distant-2"), ("head", "8 deg", 8, "head-distant-8"),
        ("shell", "point", 0, "shell-point"), ("shell", "r 20", 20, "shell-sphere")]
results = {}  # scene -> technique -> entry
order = []
for _, _, _, scene in rows:
    entries = json.load(open(os.path.join(out, scene, "report.json")))["techniques"]
    update = os.path.join(out, scene + "-update", "report.json")
    if os.path.exists(update):  # rows rendered again (ONLY=...) replace the first ones
        newer = {e["technique"]: e for e in json.load(open(update))["techniques"]}
        entries = [newer.get(e["technique"], e) for e in entries]
    entries += [dict(e, technique=f"shadow-rays x{samples}" if e["technique"] == "shadow-rays"
                     else e["technique"] + " soft=auto")
                for e in json.load(open(os.path.join(out, scene + "-samples", "report.json")))["techniques"]]
    results[scene] = {e["technique"]: e for e in entries}
    for e in entries:
        if e["technique"] not in order:
            order.append(e["technique"])
# In the table, not the plot: no light shadows (emission-absorption, phong,
# sat-ao's ambient occlusion) or an isosurface instead of DVR (occlusion-map
# at its default mode=iso), so their errors, 5-40 dE, are not about shadows
# and would squash the plot's scale.
unplotted = {"emission-absorption", "phong", "sat-ao", "occlusion-map"}
def cell(e):
    return f"{e['mean_de']:.2f} / {e['p99_de']:.1f} / {e['frame_ms']:.0f}"
lines = []
for volume in ("engine", "head", "shell"):
    vrows = [r for r in rows if r[0] == volume]
    lines.append(f"| {volume}: technique | " + " | ".join(f"light {r[1]}: dE mean / p99 / ms" for r in vrows) + " |")
    lines.append("|---" * (len(vrows) + 1) + "|")
    for t in order:
        lines.append(f"| {t} | " + " | ".join(cell(results[r[3]][t]) if t in results[r[3]] else "-" for r in vrows)
                     + " |")
    lines.append("")
    with open(os.path.join(out, f"soft-shadow-{volume}.csv"), "w") as f:
        f.write("series,x,y\n")
        for t in [t for t in order if t not in unplotted]:
            for r in vrows:
                if t in results[r[3]]:
                    f.write(f"{t},{r[2]},{results[r[3]][t]['mean_de']}\n")
open(os.path.join(out, "soft-shadows.md"), "w").write("\n".join(lines))
print("\n".join(lines))
PY
for volume in engine head; do
  "$bin" plot "$out/soft-shadow-$volume.csv" -o "$out/soft-shadow-$volume.png" \
    --title "$volume CT: error against the path-traced reference" --x-label "light angle_deg (cone half-angle)" \
    --y-label "mean dE" --size 760x440
done
"$bin" plot "$out/soft-shadow-shell.csv" -o "$out/soft-shadow-shell.png" \
  --title "shell: error against the path-traced reference" --x-label "sphere light radius" --y-label "mean dE" \
  --size 760x440
