#!/usr/bin/env python3
"""Frame time and memory of ipsvi's two light models (light_model=grey|paper), with and without the scattered part.

Usage (from the checkout, after `make`):
  PYTHONPATH=build/python /usr/bin/python3 scripts/ipsvi-light-models.py [SIZE]
Prints a markdown table: scene, parameters, frame ms (median of 3 after a first render), aux MiB.
"""
import statistics
import sys
import time
from pathlib import Path

import penumbra


def main():
    root = Path(__file__).resolve().parent.parent
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 256
    print("| scene | parameters | frame ms | aux MiB |")
    print("|---|---|---|---|")
    for name in ("engine", "head-directional", "shell-directional"):
        scene = penumbra.Scene(str(root / "scenes" / f"{name}.json"), size=(size, size))
        for params in ({}, {"light_model": "paper"}, {"albedo": 0.5}, {"light_model": "paper", "albedo": 0.5}):
            renderer = penumbra.Renderer(scene, "ipsvi", **params)
            renderer.render()
            times = []
            for _ in range(3):
                start = time.perf_counter()
                renderer.render()
                times.append(time.perf_counter() - start)
            label = ", ".join(f"{k}={v}" for k, v in params.items()) or "defaults (grey)"
            print(f"| {name} | {label} | {statistics.median(times) * 1000:.0f} | "
                  f"{renderer.stats['aux_bytes'] / 2**20:.2f} |", flush=True)


if __name__ == "__main__":
    main()
