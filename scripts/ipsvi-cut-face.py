#!/usr/bin/env python3
"""ipsvi on faces the light grazes (issue 21): error against exact shadow rays
and frame time, per line width, beside shadow-rays' own frame time.

Usage (from the checkout, after `make`):
  PYTHONPATH=build/python /usr/bin/python3 scripts/ipsvi-cut-face.py [SCENE.json ...]
Default scenes: scenes/ipsvi-engine-cut.json (the engine cut at x = 10, light
84 degrees from the face's normal), scenes/engine.json, scenes/head-directional.json.
Environment: SIZE=256x256, WIDTHS="1 4 16", RUNS=3 (median frame time).
"""
import os
import statistics
import sys
import time
from pathlib import Path

import penumbra


def main():
    root = Path(__file__).resolve().parent.parent
    width, height = (int(v) for v in os.environ.get("SIZE", "256x256").split("x"))
    widths = [int(w) for w in os.environ.get("WIDTHS", "1 4 16").split()]
    runs = int(os.environ.get("RUNS", "3"))
    paths = sys.argv[1:] or [str(root / "scenes" / n) for n in
                             ("ipsvi-engine-cut.json", "engine.json", "head-directional.json")]

    def timed(renderer):
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            image = renderer.render()
            times.append(time.perf_counter() - start)
        return image, statistics.median(times)

    print(f"| scene | technique | mean dE | p99 dE | frame s (median of {runs}) |")
    print("|---|---|---|---|---|")
    for path in paths:
        scene = penumbra.Scene(path, size=(width, height))
        name = Path(path).stem
        reference, seconds = timed(penumbra.Renderer(scene, "shadow-rays", shadow_cache=False))
        print(f"| {name} | shadow-rays (exact, the reference) | 0 | 0 | {seconds:.2f} |", flush=True)
        for line_width in widths:
            image, seconds = timed(penumbra.Renderer(scene, "ipsvi", line_width=line_width))
            d = penumbra.compare_images(image, reference)
            print(f"| {name} | ipsvi line_width {line_width} | {d['mean_de']:.3f} | {d['p99_de']:.2f} "
                  f"| {seconds:.2f} |", flush=True)


if __name__ == "__main__":
    main()
