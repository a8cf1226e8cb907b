"""Frame time of filtered-sat, and the rebuild a filter change costs, against its filter size.

    PYTHONPATH=build/python /usr/bin/python3 examples/filter_size_timing.py [out.png]

One Renderer keeps its tables; update(params=...) changes the filter, which
rebuilds only what depends on it. Times are medians of a few frames (this is
a sketch, not a benchmark: `penumbra bench` and docs/PERFORMANCE.md are).
With Debian's python3-matplotlib the numbers are plotted; without it they are
printed.
"""
import statistics
import sys

import penumbra

FILTERS = [3, 5, 9, 15, 25, 41]
FRAMES = 5


def main():
    scene = penumbra.Scene(volume={"builtin": "spheres", "size": [96, 96, 96]}, size=(192, 192),
                           transfer_function=[[0.0, 1, 1, 1, 0.0], [0.4, 1, 0.7, 0.4, 0.0], [1.0, 1, 1, 1, 0.9]],
                           lights=[{"type": "directional", "direction": [-0.5, 0.6, -0.6]}])
    renderer = penumbra.Renderer(scene, "filtered-sat")
    renderer.render()  # builds the SAT tables once; a filter change rebuilds only the visibility cache
    frame_ms, prepare_ms = [], []
    for size in FILTERS:
        renderer.update(params={"filter_voxels": size})
        renderer.prepare()  # rebuilds for the new filter
        prepare_ms.append(renderer.stats["prepare_ms"])
        times = []
        for _ in range(FRAMES):
            renderer.orbit(2.0)  # a new view: no light-space rebuild
            renderer.render()
            times.append(renderer.stats["frame_ms"])
        frame_ms.append(statistics.median(times))
        print(f"filter_voxels {size:3d}: frame {frame_ms[-1]:7.1f} ms, rebuild {prepare_ms[-1]:7.1f} ms")
    try:
        import matplotlib
        if len(sys.argv) > 1:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (apt-get install python3-matplotlib); numbers above")
        return
    figure, axis = plt.subplots(figsize=(5, 3.5))
    axis.plot(FILTERS, frame_ms, "o-", label="frame (median)")
    axis.plot(FILTERS, prepare_ms, "s--", label="rebuild after the filter changes")
    axis.set_xlabel("filter_voxels")
    axis.set_ylabel("ms")
    axis.set_title(f"filtered-sat, {penumbra.thread_count()} threads")
    axis.legend()
    figure.tight_layout()
    if len(sys.argv) > 1:
        figure.savefig(sys.argv[1], dpi=100)
        print(sys.argv[1])
    else:
        plt.show()


if __name__ == "__main__":
    main()
