"""Render a numpy volume with three techniques side by side.

    PYTHONPATH=build/python /usr/bin/python3 examples/three_techniques.py [out.png]

The volume is made here (a torus around a ball, as an array[z, y, x]); any
array from nibabel, pydicom, SimpleITK or h5py works the same way. With
Debian's python3-matplotlib the three images go into one figure (shown, or
saved to out.png); without it each image is written as a PNG.
"""
import sys

import numpy as np

import penumbra


def make_volume(n=96):
    z, y, x = np.meshgrid(*(np.linspace(-1, 1, n),) * 3, indexing="ij")
    ring = np.hypot(np.hypot(x, y) - 0.6, z)
    ball = np.sqrt(x * x + y * y + (z + 0.1) ** 2)
    density = np.maximum(np.clip(1 - ring / 0.2, 0, 1), np.clip(1 - ball / 0.35, 0, 1))
    return (255 * density).astype(np.uint8)  # no copy: the Volume reads this array


def main():
    volume = penumbra.Volume(make_volume(), spacing=(1.0, 1.0, 1.0))
    scene = penumbra.Scene(
        volume=volume,
        transfer_function=[[0.0, 1.0, 0.6, 0.3, 0.0], [0.2, 1.0, 0.6, 0.3, 0.0], [0.5, 1.0, 0.8, 0.5, 0.3],
                           [1.0, 1.0, 1.0, 1.0, 0.9]],
        lights=[{"type": "directional", "direction": [-0.6, 0.5, -0.7], "intensity": 1.2}],
        material={"ambient": 0.15},
        planes=[{"point": [0, 0, -52], "normal": [0, 0, 1], "color": [0.8, 0.8, 0.8]}],
        size=(256, 256))
    techniques = [("phong", {}), ("shadow-rays", {}), ("filtered-sat", {"filter_voxels": 9})]
    images = []
    for name, params in techniques:
        renderer = penumbra.Renderer(scene, name, **params)
        images.append((name, renderer.render(), renderer.stats["frame_ms"]))
        print(f"{name}: {renderer.stats['frame_ms']:.0f} ms")
    try:
        import matplotlib
        if len(sys.argv) > 1:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        for name, image, _ in images:
            penumbra.write_image(f"{name}.png", image)
        print("matplotlib is not installed (apt-get install python3-matplotlib); wrote one PNG per technique")
        return
    figure, axes = plt.subplots(1, len(images), figsize=(4 * len(images), 4.4))
    for axis, (name, image, ms) in zip(axes, images):
        axis.imshow(image.to_srgb8())
        axis.set_title(f"{name} ({ms:.0f} ms)")
        axis.axis("off")
    figure.tight_layout()
    if len(sys.argv) > 1:
        figure.savefig(sys.argv[1], dpi=100)
        print(sys.argv[1])
    else:
        plt.show()


if __name__ == "__main__":
    main()
