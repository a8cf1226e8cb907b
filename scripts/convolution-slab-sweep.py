#!/usr/bin/env python3
"""convolution's error against its slab distance: each distance against one
render at a quarter of the smallest, mean / p99 dE and frame time.

Usage: PYTHONPATH=build/python python3 scripts/convolution-slab-sweep.py SCENE SIZE E1,E2,...
"""
import sys
import time

import penumbra


def main():
    path, size = sys.argv[1], int(sys.argv[2])
    distances = [float(x) for x in sys.argv[3].split(",")]
    scene = penumbra.Scene(path, size=(size, size))
    reference = penumbra.Renderer(scene, "convolution", slab_distance=min(distances) / 4).render()
    for e in distances:
        renderer = penumbra.Renderer(scene, "convolution", slab_distance=e)
        start = time.perf_counter()
        image = renderer.render()
        ms = (time.perf_counter() - start) * 1000
        m = penumbra.compare_images(image, reference)
        print(f"e {e:g} voxels: mean dE {m['mean_de']:.3f}, p99 {m['p99_de']:.2f}, {ms:.0f} ms")


if __name__ == "__main__":
    main()
