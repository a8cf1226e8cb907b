#!/usr/bin/env python3
"""Weidner & Linsen's Fig. 2 and their deep-shadow-map-vs-CSSM comparison (issue 16).

Quality against two references and memory, for deep-shadow-map with NODES nodes
and cssm with OFFSETS offsets (the paper's filter and the depth-aware one), at
map resolutions RESOLUTIONS, on SCENES. Each configuration builds its map once
(one penumbra.Renderer, one prepare and one render) and is measured against
both references in memory, so a 4096² row costs one map build.

References, rendered once per scene at SIZE:
  converged-dsm  deep-shadow-map, 16 nodes, tolerance 0.002, bilinear, at
                 REF_RESOLUTION (default 2048), the same colour model: a
                 converged coloured deep shadow map, what both approximate
  shadow-rays    the physical model's grey transmittance, marched per sample
                 (shadow_cache=false: exact, no cache interpolation)

Output: a markdown table on stdout (mean and p99 CIEDE2000 against each
reference, memory in MiB from aux_bytes, map build time in s), the images
under OUT (EXR, linear).

Environment (all optional): SIZE=192x192 OUT=/tmp/shadow-maps-fig2
  SCENES="head-point shell-point" RESOLUTIONS="512 1024 2048" NODES="2 3 4 8"
  OFFSETS="7 13 21" FILTERS="paper depth-aware" REF_RESOLUTION=2048
  COLOR_MODEL=chromatic|paper|grey (grey: colored=false, the transmittance
  shadow-rays marches, the fairest comparison with it)
Run from the checkout after `make` (the package is build/python/penumbra);
scripts/shadow-maps-fig2.sh sets PYTHONPATH and runs this with /usr/bin/python3.
"""
import os
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import penumbra


def words(name, default):
    return os.environ.get(name, default).split()


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def load():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"


def main():
    root = Path(__file__).resolve().parent.parent
    width, height = (int(v) for v in os.environ.get("SIZE", "192x192").split("x"))
    out = Path(os.environ.get("OUT", "/tmp/shadow-maps-fig2"))
    scenes = words("SCENES", "head-point shell-point")
    resolutions = [int(r) for r in words("RESOLUTIONS", "512 1024 2048")]
    node_counts = [int(n) for n in words("NODES", "2 3 4 8")]
    offset_counts = [int(n) for n in words("OFFSETS", "7 13 21")]
    filters = words("FILTERS", "paper depth-aware")
    ref_resolution = int(os.environ.get("REF_RESOLUTION", "2048"))
    color_model = os.environ.get("COLOR_MODEL", "chromatic")
    if color_model not in ("chromatic", "paper", "grey"):
        sys.exit(f"shadow-maps-fig2: COLOR_MODEL={color_model!r}: use chromatic, paper or grey")
    color = {"colored": False} if color_model == "grey" else {"color_model": color_model}

    print(f"# {datetime.now(timezone.utc):%Y-%m-%dT%H:%MZ}, {os.cpu_count()} cores, {cpu_model()}, "
          f"load {load()}, image {width}x{height}, colour model {color_model}")
    print("| scene | technique | map | mean dE vs converged DSM | p99 | mean dE vs shadow-rays | p99 "
          "| memory MiB | build s |")
    print("|---|---|---|---|---|---|---|---|---|")
    sys.stdout.flush()
    for name in scenes:
        scene = penumbra.Scene(root / "scenes" / f"{name}.json", size=(width, height))
        folder = out / name
        folder.mkdir(parents=True, exist_ok=True)

        def render(technique, label, **params):
            renderer = penumbra.Renderer(scene, technique, **params)
            start = time.perf_counter()
            renderer.prepare()
            build_s = time.perf_counter() - start
            image = renderer.render()
            penumbra.write_image(folder / f"{label}.exr", image)
            return image, renderer.stats["aux_bytes"], build_s

        converged, _, _ = render("deep-shadow-map", "converged-dsm", nodes=16, tolerance=0.002, filter="bilinear",
                                 resolution=ref_resolution, **color)
        shadow_rays, _, _ = render("shadow-rays", "shadow-rays", shadow_cache=False)

        def row(label, technique, **params):
            tag = "-".join(f"{k}-{v}" for k, v in params.items())
            image, aux_bytes, build_s = render(technique, f"{technique}-{tag}", **params)
            a = penumbra.compare_images(image, converged)
            b = penumbra.compare_images(image, shadow_rays)
            print(f"| {name} | {label} | {a['mean_de']:.2f} | {a['p99_de']:.1f} | {b['mean_de']:.2f} "
                  f"| {b['p99_de']:.1f} | {aux_bytes / 2**20:.1f} | {build_s:.1f} |")
            sys.stdout.flush()

        for resolution in resolutions:
            for nodes in node_counts:
                row(f"deep-shadow-map {nodes} nodes | {resolution}²", "deep-shadow-map", resolution=resolution,
                    nodes=nodes, **color)
            for offsets in offset_counts:
                for filter_name in filters:
                    row(f"cssm {offsets} offsets, {filter_name} | {resolution}²", "cssm", resolution=resolution,
                        offsets=str(offsets), filter=filter_name, **color)
    print(f"# load after: {load()}")


if __name__ == "__main__":
    main()
