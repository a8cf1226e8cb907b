"""penumbra: direct volume rendering with advanced illumination, from Python.

A thin layer over penumbra's C++ engine (the same code as the `penumbra` CLI
and server)::

    import numpy as np, penumbra
    volume = penumbra.Volume(np.load("ct.npy"), spacing=(0.5, 0.5, 1.0))  # array[z, y, x], no copy
    scene = penumbra.Scene(volume=volume, transfer_function=[[0.3, 1, 0.8, 0.6, 0.0], [1, 1, 1, 1, 0.8]],
                           lights=[{"type": "directional", "direction": [-1, -1, -1]}], size=(256, 256))
    renderer = penumbra.Renderer(scene, "filtered-sat", filter_voxels=9)
    image = renderer.render()                  # (256, 256, 4) float32, linear; shows itself in Jupyter
    renderer.update(lights=[{"type": "directional", "direction": [1, -1, -1]}])
    image = renderer.render()                  # rebuilds only what depends on the lights
    print(renderer.stats["light_move_ms"])

Scenes are scene JSON v1 (docs/scene-format.md) as dicts; errors are Python
exceptions carrying the C++ message: OSError (FileError) for files, ValueError
(SceneError, ParameterError) for bad keys and parameters, MemoryError
(MemoryBudgetError) for the memory budget.
"""
from ._penumbra import (
    FileError,
    MemoryBudgetError,
    ParameterError,
    ParameterSpec,
    SceneError,
    TechniqueInfo,
    Volume,
    compare_images,
    delta_e_2000,
    encode_png,
    memory_budget,
    psnr,
    read_volume,
    rmse,
    set_memory_budget,
    set_threads,
    ssim,
    supported_volume_extensions,
    technique,
    techniques,
    thread_count,
)
from .image import Image, read_image, to_srgb8, write_image
from .scene import Scene
from .renderer import Renderer, compare

__version__ = "0.1.0"

__all__ = [
    "FileError", "Image", "MemoryBudgetError", "ParameterError", "ParameterSpec", "Renderer", "Scene", "SceneError",
    "TechniqueInfo", "Volume", "compare", "compare_images", "delta_e_2000", "encode_png", "memory_budget", "psnr",
    "read_image", "read_volume", "rmse", "set_memory_budget", "set_threads", "ssim", "supported_volume_extensions",
    "technique", "techniques", "thread_count", "to_srgb8", "write_image",
]
