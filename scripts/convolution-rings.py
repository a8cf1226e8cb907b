#!/usr/bin/env python3
"""Slab rings and bands (issue 23): convolution with and without the per-pixel
jitter within slabs, against the same technique at a slab distance eight
times finer (the rings are convolution's own error, so it is its own reference).

Prints per slab distance: mean / p99 dE against the fine render; the
structured error, the RMS of the grey error box-filtered over 5x5 pixels
(bands and moire keep their amplitude, noise averages out); and, for a scene
whose first mesh is a sphere, the ring energy: the RMS of the error's
azimuthal mean about the sphere's image centre (annuli one pixel wide, less a
9-pixel moving average of that profile). Rings concentric about the centre
keep their amplitude in that mean; noise averages out over the 2 pi r pixels
of an annulus.

Usage: PYTHONPATH=build/python python3 scripts/convolution-rings.py [scene.json] [size] [e1,e2,...]
"""
import json
import sys

import numpy as np

import penumbra


def image_centre(scene_json, point, size):
    cam = scene_json["camera"]
    eye, target, up = (np.array(cam[k], float) for k in ("eye", "target", "up"))
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    d = np.array(point, float) - eye
    half = np.tan(np.radians(cam.get("fov_deg", 30.0)) / 2)
    x = np.dot(d, right) / np.dot(d, forward) / half
    y = np.dot(d, true_up) / np.dot(d, forward) / half
    return (0.5 + 0.5 * x) * size[0], (0.5 - 0.5 * y) * size[1]


def luminance(img):
    a = np.asarray(img, float)
    return 0.2126 * a[..., 0] + 0.7152 * a[..., 1] + 0.0722 * a[..., 2]


def ring_energy(error, centre, radius):
    h, w = error.shape
    yy, xx = np.mgrid[0:h, 0:w]
    r = np.hypot(xx + 0.5 - centre[0], yy + 0.5 - centre[1])
    bins = r.astype(int)
    inside = r < radius
    counts = np.bincount(bins[inside], minlength=int(radius) + 1)
    sums = np.bincount(bins[inside], weights=error[inside], minlength=int(radius) + 1)
    used = counts > 0
    profile = sums[used] / counts[used]
    smooth = np.convolve(np.pad(profile, 4, mode="edge"), np.ones(9) / 9, mode="valid")
    return float(np.sqrt(np.mean((profile - smooth) ** 2)))


def structured_error(error):
    padded = np.pad(error, 2, mode="edge")
    h, w = error.shape
    box = sum(padded[dy:dy + h, dx:dx + w] for dy in range(5) for dx in range(5)) / 25.0
    return float(np.sqrt(np.mean(box ** 2)))


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "scenes/mesh-sphere.json"
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    scene_json = json.load(open(path))
    scene = penumbra.Scene(path, size=(size, size))
    meshes = scene_json.get("meshes", [])
    cam = scene_json["camera"]
    sphere = bool(meshes) and meshes[0].get("builtin") == "sphere" and cam.get("projection") != "orthographic"
    print(f"{path} at {size}^2")
    if sphere:
        mesh = meshes[0]
        centre = image_centre(scene_json, mesh.get("translate", [0, 0, 0]), (size, size))
        # The sphere's image radius, roughly: scale over distance over tan(fov / 2).
        dist = np.linalg.norm(np.array(cam["eye"], float) - np.array(mesh.get("translate", [0, 0, 0]), float))
        radius = 0.5 * size * mesh["scale"] / dist / np.tan(np.radians(cam.get("fov_deg", 30.0)) / 2)
        print(f"  sphere centre ({centre[0]:.1f}, {centre[1]:.1f}) px, radius {radius:.1f} px")
    for e in (float(x) for x in (sys.argv[3].split(",") if len(sys.argv) > 3 else ["1", "2", "4"])):
        fine = penumbra.Renderer(scene, "convolution", slab_distance=e / 8, jitter="off").render()
        fine_l = luminance(fine)
        for jitter in ("off", "on"):
            img = penumbra.Renderer(scene, "convolution", slab_distance=e, jitter=jitter).render()
            m = penumbra.compare_images(img, fine)
            error = luminance(img) - fine_l
            line = (f"  e {e:g} voxels, jitter {jitter:3}: mean dE {m['mean_de']:.3f}, p99 {m['p99_de']:.2f}, "
                    f"structured {structured_error(error) * 1000:.2f}e-3")
            if sphere:
                line += f", ring energy {ring_energy(error, centre, 0.98 * radius) * 1000:.2f}e-3"
            print(line)
            penumbra.write_image(f"/tmp/conv-rings-e{e:g}-{jitter}.png", img)
    penumbra.write_image("/tmp/conv-rings-fine.png", fine)


if __name__ == "__main__":
    main()
