#!/usr/bin/env bash
# filtered-sat and its SAT baselines in the shape of Ament et al. 2014,
# Table 1: for the engine CT, the head CT and the 256^3 synthetic volume at
# 512 x 512, with three orthodirectional lights and with two point lights,
# the table memory, the TF-change and light-move times (the shadow structures'
# rebuild) and the frame time of shadow-rays (with its cache), sat-ao,
# cone-shadows and filtered-sat, all with shadow caches at half the data
# resolution and the SATs at half resolution, as in the paper's comparisons.
# Then filtered-sat's TF-change time for filters of 3, 9 and 15 voxels.
# With `compare`: the soft-light comparison of docs/filtered-sat.md instead
# (the engine CT under a distant light of 3 degrees half-angle, pathtrace
# single scattering as the reference, shadow-rays, filtered-sat with the box of
# matching width and cone-shadows with the matching cone).
#
# Usage: scripts/bench-filtered-sat.sh [RUNS]        (default 1; medians over runs)
#        scripts/bench-filtered-sat.sh compare        (minutes: the reference is path traced)
#   PENUMBRA=path/to/penumbra   the binary (default build/penumbra)
#   OUT=dir                     scenes and raw results (default build/bench-filtered-sat)
#   SCENES="engine-3ol ..."     the Table 1 rows to run (default: the engine and head rows, about 3 minutes per
#                               run on a quiet 2-core machine; SCENES=all adds the 256^3 synthetic volume,
#                               about 6-7 minutes: shadow-rays' and cone-shadows' caches dominate)
# Needs ../shared/data (engine, head) and build/peer/synth256.nrrd (made by
# scripts/bench-vs-vtk.sh, which needs VTK); missing volumes are skipped.
# Prints the markdown tables of docs/PERFORMANCE.md ("filtered-sat, sat-ao,
# cone-shadows").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${PENUMBRA:-$root/build/penumbra}
out=${OUT:-$root/build/bench-filtered-sat}
mkdir -p "$out"

if [ "${1:-}" = compare ]; then
  # A uniform cone of half-angle theta blurs a shadow cast over a distance D
  # into a disk of radius D theta, variance (D theta)^2 / 4 per axis; the box
  # of width w has w^2 / 12. The engine sits about 80 voxels above its floor:
  # theta = 3 degrees matches w = sqrt(3) * 80 * 0.052 = 7 voxels.
  python3 - "$root" "$out" <<'PY'
import json, os, sys
root, out = sys.argv[1], sys.argv[2]
scene = json.load(open(os.path.join(root, "scenes", "engine.json")))
scene["volume"] = {"file": os.path.normpath(os.path.join(root, "..", "shared", "data", "engine_256x256x128_uint8.nhdr"))}
scene["lights"] = [{"type": "distant", "direction": [0.45, 0.55, -1.0], "angle_deg": 3.0, "profile": "uniform",
                    "intensity": 1.6}]
scene["material"] = {"shading": "phase", "ambient": 0.0}
scene["render"] = {"width": 192, "height": 192, "step": 0.5, "ert_threshold": 1.0, "technique": "pathtrace",
                   "params": {"mode": "single", "spp": 4096, "min_spp": 64, "target_error": 0.6}}
json.dump(scene, open(os.path.join(out, "engine-soft.json"), "w"), indent=1)
PY
  "$bin" compare "$out/engine-soft.json" --techniques shadow-rays,filtered-sat,cone-shadows \
    --param filtered-sat.filter_voxels=7 --param cone-shadows.cone_angle_deg=3 --param sat_resolution=0.5 --frames 1 \
    -o "$out/compare"
  # filtered-sat's filter size against the same reference.
  for filter in 1 3 7 15; do
    "$bin" compare "$out/engine-soft.json" --reference-image "$out/compare/reference.exr" --techniques filtered-sat \
      --param filter_voxels=$filter --param sat_resolution=0.5 --frames 1 -o "$out/compare-filter-$filter" |
      grep 'mean dE' | sed "s/^/filter $filter: /"
  done
  exit 0
fi

runs=${1:-1}
scenes=${SCENES:-"engine-3ol engine-2pl head-3ol head-2pl"}
[ "$scenes" = all ] && scenes="engine-3ol engine-2pl head-3ol head-2pl synth-3ol synth-2pl"
results=$out/results.jsonl
: > "$results"

# Scenes: each base scene's volume, TF, camera and material, with absolute
# volume paths and the two lighting setups.
python3 - "$root" "$out" <<'PY'
import json, math, os, sys
root, out = sys.argv[1], sys.argv[2]
data = os.path.normpath(os.path.join(root, "..", "shared", "data"))

def norm(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]

def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

def ortho_lights(key):
    # Key, fill and back light along three mutually orthogonal directions.
    k = norm(key)
    f = norm(cross(k, [0.0, 0.0, 1.0]))
    b = cross(k, f)
    return [{"type": "directional", "direction": k, "intensity": 1.0},
            {"type": "directional", "direction": f, "intensity": 0.5},
            {"type": "directional", "direction": b, "intensity": 0.35}]

def point_lights(positions):
    return [{"type": "point", "position": p, "intensity": 0.8 * sum(c * c for c in p)} for p in positions]

engine = json.load(open(os.path.join(root, "scenes", "engine.json")))
engine["volume"] = {"file": os.path.join(data, "engine_256x256x128_uint8.nhdr")}
head = {
    "volume": {"file": os.path.join(data, "ct_head_cranium_256x256x108_int16.nhdr")},
    "transfer_function": {
        "points": [[0.0, 0.0, 0.0, 0.0, 0.0], [0.233, 0.9, 0.55, 0.45, 0.0], [0.30, 0.9, 0.55, 0.45, 0.003],
                   [0.367, 0.85, 0.45, 0.4, 0.005], [0.417, 0.9, 0.7, 0.6, 0.005], [0.467, 1.0, 0.95, 0.85, 0.5],
                   [1.0, 1.0, 1.0, 0.95, 0.9]],
        "range": [-1000, 2000]},
    "camera": {"eye": [430, 470, 170], "target": [0, 10, -15], "up": [0, 0, 1], "fov_deg": 30},
    "material": {"shading": "phase", "ambient": 0.15},
    "render": {"width": 512, "height": 512, "step": 0.5},
    "planes": [{"point": [0, 0, -85], "normal": [0, 0, 1], "color": [0.6, 0.6, 0.6]}],
    "background": [0.02, 0.02, 0.03]}
synth = json.load(open(os.path.join(root, "scenes", "peer_synthetic.json")))
synth["volume"] = {"file": os.path.join(root, "build", "peer", "synth256.nrrd")}
synth["render"].pop("technique", None)

setups = {
    "engine": (engine, [0.45, 0.55, -1.0], [[200, -250, 300], [-300, -150, 150]]),
    "head": (head, [0.2, -0.7, -1.0], [[250, -300, 250], [-300, -200, 100]]),
    "synth": (synth, [-0.47, -0.34, -0.81], [[300, 250, 450], [-400, 100, 250]]),
}
for name, (base, key, points) in setups.items():
    for suffix, lights in (("3ol", ortho_lights(key)), ("2pl", point_lights(points))):
        scene = json.loads(json.dumps(base))
        scene["lights"] = lights
        scene["render"]["width"] = scene["render"]["height"] = 512
        scene["render"].pop("params", None)
        json.dump(scene, open(os.path.join(out, "%s-%s.json" % (name, suffix)), "w"), indent=1)
PY

volume_of() {
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["volume"]["file"])' "$1"
}

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "# load before: $(uptime | sed 's/.*load average: //')"
for run in $(seq 1 "$runs"); do
  for scene in $scenes; do
    file=$out/$scene.json
    if [ ! -f "$(volume_of "$file")" ]; then
      echo "# skipping $scene: no $(volume_of "$file")" >&2
      continue
    fi
    "$bin" bench "$file" --technique shadow-rays --technique sat-ao --technique cone-shadows --technique filtered-sat \
      --param shadow-rays.shadow_cache=true --param sat_resolution=0.5 --frames 3 |
      sed "s/^{/{\"scene\": \"$scene\", \"run\": $run, /" >> "$results"
  done
  # The cost of a TF change does not depend on the filter size (small images:
  # only the prepare times are reported here).
  if [ -f "$(volume_of "$out/engine-3ol.json")" ]; then
    for filter in 3 9 15; do
      "$bin" bench "$out/engine-3ol.json" --technique filtered-sat --param sat_resolution=0.5 \
        --param filter_voxels=$filter --size 128x128 --frames 1 |
        sed "s/^{/{\"scene\": \"engine-3ol\", \"filter\": $filter, \"run\": $run, /" >> "$results"
      "$bin" bench "$out/engine-3ol.json" --technique filtered-sat --param sat_resolution=0.5 \
        --param filter_voxels=$filter --param kernel=gaussian --size 128x128 --frames 1 |
        sed "s/^{/{\"scene\": \"engine-3ol\", \"filter\": $filter, \"kernel\": \"gaussian\", \"run\": $run, /" >> "$results"
    done
    # The tables alone (no shadow cache): how much of a TF change they are.
    for scene in engine-3ol engine-2pl; do
      "$bin" bench "$out/$scene.json" --technique filtered-sat --param sat_resolution=0.5 --param shadow_cache=false \
        --size 128x128 --frames 1 |
        sed "s/^{/{\"scene\": \"$scene\", \"tables_only\": true, \"run\": $run, /" >> "$results"
    done
  fi
done
echo "# load after: $(uptime | sed 's/.*load average: //')"

python3 - "$results" <<'PY'
import json, math, statistics, sys
rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]

def cache_bytes(row, lights):
    # Caches at half the data resolution (the default cache_resolution 0.5),
    # float texels; one per light, one in all for sat-ao.
    texels = math.prod(max(2, math.ceil(d * 0.5)) for d in row["dims"])
    return 4 * texels * (1 if row["technique"] == "sat-ao" else lights)

def median(rows, key):
    return statistics.median(r[key] for r in rows)

names = {"engine": "Engine CT", "head": "Head CT", "synth": "Synthetic"}
order = ["shadow-rays", "sat-ao", "cone-shadows", "filtered-sat"]
print("| data set | resolution | lights | SAT MB AO/CS | SAT MB FS | TF change ms SS / AO / CS / FS |"
      " light move ms SS / AO / CS / FS | frame ms SS / AO / CS / FS |")
print("|---|---|---|---|---|---|---|---|")
for scene in ["engine-3ol", "engine-2pl", "head-3ol", "head-2pl", "synth-3ol", "synth-2pl"]:
    by = {t: [r for r in rows if r.get("scene") == scene and r["technique"] == t and "filter" not in r
              and "tables_only" not in r] for t in order}
    if not all(by.values()):
        continue
    lights = 3 if scene.endswith("3ol") else 2
    first = by["filtered-sat"][0]
    sat = {t: (by[t][0]["aux_bytes"] - cache_bytes(by[t][0], lights)) / 2**20 for t in ("sat-ao", "filtered-sat")}
    cell = lambda key: " / ".join("%.0f" % median(by[t], key) if median(by[t], key) >= 1 else "-" for t in order)
    print("| %s | %s | %s | %.1f | %.1f | %s | %s | %s |" % (
        names[scene.split("-")[0]], "x".join(map(str, first["dims"])),
        "3 OLs" if lights == 3 else "2 PLs", sat["sat-ao"], sat["filtered-sat"],
        cell("tf_change_ms"), cell("light_move_ms"), cell("frame_ms_median")))
print()
print("| filter (voxels) | box: TF change ms | box: light move ms | gaussian: TF change ms |")
print("|---|---|---|---|")
for f in (3, 9, 15):
    box = [r for r in rows if r.get("filter") == f and "kernel" not in r]
    gauss = [r for r in rows if r.get("filter") == f and r.get("kernel") == "gaussian"]
    if box:
        print("| %d | %.0f | %.0f | %s |" % (f, median(box, "tf_change_ms"), median(box, "light_move_ms"),
                                             "%.0f" % median(gauss, "tf_change_ms") if gauss else "-"))
print()
print("| filtered-sat without shadow cache | TF change ms (the tables alone) | SAT MB |")
print("|---|---|---|")
for scene in ("engine-3ol", "engine-2pl"):
    t = [r for r in rows if r.get("scene") == scene and r.get("tables_only")]
    if t:
        print("| %s | %.0f | %.1f |" % (scene, median(t, "tf_change_ms"), t[0]["aux_bytes"] / 2**20))
print()
print("runs per cell: %d (medians over runs; each run's TF change and light move are medians of 3 prepares)"
      % max(1, len({r["run"] for r in rows})))
PY
