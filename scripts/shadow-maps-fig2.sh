#!/usr/bin/env bash
# Weidner & Linsen's Fig. 2 and their deep-shadow-map-vs-CSSM comparison as an
# experiment (issue 16); the experiment itself is scripts/shadow-maps-fig2.py
# (its docstring lists the settings: SIZE, OUT, SCENES, RESOLUTIONS, NODES,
# OFFSETS, FILTERS, REF_RESOLUTION, COLOR_MODEL). It runs on the Python package
# of the build folder BUILD (default build/, made by `make`), one map build per
# row.
#
# Usage: [BUILD=build] [SCENES=...] [RESOLUTIONS=...] scripts/shadow-maps-fig2.sh > table.md
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
if [ ! -f "$build/python/penumbra/__init__.py" ]; then
  echo "shadow-maps-fig2: no Python package under $build/python (run make, with pybind11-dev and python3-numpy)" >&2
  exit 2
fi
PYTHONPATH=$build/python${PYTHONPATH:+:$PYTHONPATH} exec /usr/bin/python3 "$root/scripts/shadow-maps-fig2.py"
