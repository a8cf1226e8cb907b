"""Shared fixtures: small procedural scenes, the CLI binary and the source tree.

CTest runs these with PYTHONPATH at build/python and PENUMBRA_CLI,
PENUMBRA_SOURCE_DIR set (python/CMakeLists.txt).
"""
import os
import pathlib

import numpy as np
import pytest

import penumbra

SOURCE_DIR = pathlib.Path(os.environ.get("PENUMBRA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))

# A translucent orange-to-white TF over [0, 1] of the data range.
TF_POINTS = [[0.0, 1.0, 0.5, 0.2, 0.0], [0.3, 1.0, 0.5, 0.2, 0.0], [0.6, 1.0, 0.8, 0.6, 0.4], [1.0, 1.0, 1.0, 1.0, 0.8]]
LIGHT = {"type": "directional", "direction": [-0.5, 0.7, -0.6]}


def small_scene(size=(32, 24), volume=None, **keywords):
    """The procedural spheres (24^3) with one light, at a small image size."""
    if volume is None:
        volume = {"builtin": "spheres", "size": [24, 24, 24]}
    keywords.setdefault("transfer_function", TF_POINTS)
    keywords.setdefault("lights", [LIGHT])
    keywords.setdefault("material", {"ambient": 0.1})
    return penumbra.Scene(volume=volume, size=size, **keywords)


def blob(shape=(20, 18, 16), dtype=np.float32):
    """A smooth blob, array[z, y, x] with values 0 .. 1 (scaled for integer types)."""
    z, y, x = np.meshgrid(*(np.linspace(-1, 1, n) for n in shape), indexing="ij")
    values = np.clip(1.0 - np.sqrt(x * x + 1.5 * y * y + 2.0 * z * z), 0.0, 1.0)
    if np.issubdtype(dtype, np.integer):
        values = values * min(np.iinfo(dtype).max, 1000)
    return np.ascontiguousarray(values.astype(dtype))


@pytest.fixture
def scene():
    return small_scene()


@pytest.fixture
def cli():
    path = os.environ.get("PENUMBRA_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("PENUMBRA_CLI is not set (CTest sets it to the penumbra binary)")
    return path
