#!/usr/bin/env python3
"""ipsvi against shadow-rays near equal error (issue 21): mean / p99 CIEDE2000 against the stored path-traced
references (scenes/reference/), frame time, prepare time and memory, on the engine and head CT at 256^2.

Rows: shadow-rays with exact shadow rays and with its shadow cache at three resolutions; ipsvi at three line
widths. Frame ms: median of 3 render() calls after one prepare() (whose time is "prepare ms").

Usage (from the checkout, after `make`):
  PYTHONPATH=build/python /usr/bin/python3 scripts/ipsvi-equal-error.py [SIZE]
SIZE must be the references' 256 for the dE columns to mean anything. About 5 minutes on 2 cores, most of it
the shadow cache at cache_resolution 2 (35-40 s per build).
"""
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import penumbra

ROWS = (
    ("shadow-rays", "exact", {"shadow_cache": False}),
    ("shadow-rays", "cache_resolution 0.5", {"shadow_cache": True, "cache_resolution": 0.5}),
    ("shadow-rays", "cache_resolution 1.0", {"shadow_cache": True, "cache_resolution": 1.0}),
    ("shadow-rays", "cache_resolution 2.0", {"shadow_cache": True, "cache_resolution": 2.0}),
    ("ipsvi", "line_width 1", {"line_width": 1}),
    ("ipsvi", "line_width 4", {"line_width": 4}),
    ("ipsvi", "line_width 16", {"line_width": 16}),
)


def main():
    root = Path(__file__).resolve().parent.parent
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 256
    print("| scene | technique | mean dE | p99 dE | frame ms | prepare ms | aux MiB |")
    print("|---|---|---|---|---|---|---|")
    for name in ("engine-directional", "head-directional"):
        scene = penumbra.Scene(str(root / "scenes" / f"{name}.json"), size=(size, size))
        reference = np.asarray(penumbra.read_image(str(root / "scenes" / "reference" / f"{name}.exr")))
        for technique, label, params in ROWS:
            renderer = penumbra.Renderer(scene, technique, **params)
            start = time.perf_counter()
            renderer.prepare()
            prepare_ms = (time.perf_counter() - start) * 1000
            times, image = [], None
            for _ in range(3):
                start = time.perf_counter()
                image = renderer.render()
                times.append(time.perf_counter() - start)
            de = penumbra.delta_e_2000(np.asarray(image), reference)
            print(f"| {name} | {technique} {label} | {de.mean():.3f} | {np.percentile(de, 99):.2f} | "
                  f"{statistics.median(times) * 1000:.0f} | {prepare_ms:.0f} | "
                  f"{renderer.stats['aux_bytes'] / 2**20:.1f} |", flush=True)


if __name__ == "__main__":
    main()
