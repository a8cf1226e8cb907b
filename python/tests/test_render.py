"""Renderers: every technique, bit-for-bit agreement with the CLI, incremental
updates, parameters, progress, Ctrl-C, threads and the memory budget."""
import os
import signal
import subprocess
import threading
import time
import warnings

import numpy as np
import pytest

import penumbra
from conftest import LIGHT, SOURCE_DIR, TF_POINTS, small_scene

# Few paths: these tests check that pathtrace runs and stops, not its noise.
QUICK = {"pathtrace": {"spp": 4, "min_spp": 2}}


@pytest.mark.parametrize("name", [t.name for t in penumbra.techniques()])
def test_every_technique_renders_a_small_procedural_volume(name):
    scene = small_scene(planes=[{"point": [0, 0, -14], "normal": [0, 0, 1]}])
    renderer = penumbra.Renderer(scene, name, **QUICK.get(name, {}))
    image = renderer.render()
    assert isinstance(image, penumbra.Image) and isinstance(image, np.ndarray)
    assert image.shape == (24, 32, 4) and image.dtype == np.float32
    assert np.isfinite(image).all()
    centre = image[8:16, 12:20]
    assert centre[..., 3].mean() > 0.2  # the spheres are in front of the camera
    assert centre[..., :3].max() > 0.05  # and lit (or emitting)
    assert renderer.stats["renders"] == 1 and renderer.stats["frame_ms"] > 0
    assert image._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    assert image[..., :3].std() > 0.02  # an image of something, not one colour


@pytest.mark.parametrize("technique, params", [("shadow-rays", []), ("filtered-sat", ["filter_voxels=5"]),
                                               ("pathtrace", ["spp=3", "min_spp=2"])])
def test_a_render_matches_the_cli_bit_for_bit(cli, tmp_path, technique, params):
    scene_file = SOURCE_DIR / "scenes" / "spheres.json"
    exr, png = tmp_path / "cli.exr", tmp_path / "cli.png"
    for out in (exr, png):
        command = [cli, "render", str(scene_file), "-o", str(out), "--size", "40x30", "--technique", technique]
        command += [arg for p in params for arg in ("--param", p)]
        subprocess.run(command, check=True, capture_output=True)
    values = dict(p.split("=") for p in params)
    renderer = penumbra.Renderer(penumbra.Scene(scene_file, size=(40, 30)), technique,
                                 **{k: float(v) for k, v in values.items()})
    image = renderer.render()
    assert np.array_equal(penumbra.read_image(exr), image)
    assert image._repr_png_() == png.read_bytes()
    assert np.array_equal(renderer.render_srgb(), penumbra.to_srgb8(image))


def test_updates_rebuild_only_what_depends_on_the_change():
    renderer = penumbra.Renderer(small_scene(), "filtered-sat")
    first = renderer.render()
    built = renderer.stats["rebuilds"]
    assert built >= 1 and renderer.stats["build_ms"] > 0
    assert renderer.stats["tf_change_ms"] is None and renderer.stats["light_move_ms"] is None

    assert renderer.orbit(20.0) == ["camera"]
    moved = renderer.render()
    assert renderer.stats["rebuilds"] == built  # the light-space tables stay
    assert not np.array_equal(moved, first)

    assert renderer.update(lights=[LIGHT], transfer_function=TF_POINTS, params={"filter_voxels": -1.0}) == []  # the defaults again
    renderer.render()
    assert renderer.stats["rebuilds"] == built  # nothing that differs: nothing rebuilt

    # filtered-sat counts its SAT tables and its visibility cache as one rebuild each.
    assert renderer.update(lights=[{"type": "directional", "direction": [0.5, 0.7, -0.6]}]) == ["lights"]
    renderer.render()
    after_light = renderer.stats["rebuilds"]
    assert after_light > built
    assert renderer.stats["light_move_ms"] is not None and renderer.stats["tf_change_ms"] is None

    points = [[v, r, g, b, 0.5 * a] for v, r, g, b, a in TF_POINTS]
    assert renderer.update(transfer_function=points) == ["transfer_function"]
    renderer.prepare()
    after_tf = renderer.stats["rebuilds"]
    assert after_tf > after_light and renderer.stats["tf_change_ms"] is not None

    assert renderer.update(params={"filter_voxels": 15}) == ["params"]
    renderer.render()
    # The filter changes the cache, not the tables; but the defaults release
    # the tables once the cache is filled, so the one light's table is built
    # again to fill the new cache (issue 22): two rebuilds.
    assert renderer.stats["rebuilds"] == after_tf + 2
    assert renderer.params["filter_voxels"] == 15


def test_techniques_that_do_not_draw_meshes_say_so():
    meshes = [{"builtin": "sphere", "scale": 8.0}]
    with pytest.warns(UserWarning, match="does not draw .*; convolution, pathtrace, shadow-rays do"):
        penumbra.Renderer(small_scene(meshes=meshes), "phong")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        penumbra.Renderer(small_scene(meshes=meshes), "convolution")
        penumbra.Renderer(small_scene(meshes=meshes), "shadow-rays")


def test_parameters_are_checked_and_named():
    scene = small_scene()
    with pytest.raises(penumbra.ParameterError) as error:
        penumbra.Renderer(scene, "filtered-sat", filter_voxel=9)
    assert error.value.name == "filter_voxel" and isinstance(error.value, ValueError)
    with pytest.raises(ValueError, match="filter_voxels"):
        penumbra.Renderer(scene, "filtered-sat", filter_voxels=-3)
    with pytest.raises(ValueError, match="teapot"):
        penumbra.Renderer(scene, "teapot")
    renderer = penumbra.Renderer(scene, "phong")
    with pytest.raises(ValueError, match="spp"):
        renderer.update(params={"spp": 3}, camera={"eye": [0, -90, 0]})
    assert renderer.scene["camera"] == scene["camera"]  # the failed update changed nothing
    with pytest.raises(penumbra.SceneError, match="render.params.no_such"):
        penumbra.Renderer(small_scene(technique="phong", params={"no_such": 1}))


def test_the_parameter_tables_describe_every_parameter():
    names = [t.name for t in penumbra.techniques()]
    assert len(names) == len(set(names)) >= 14 and {"pathtrace", "shadow-rays", "convolution"} <= set(names)
    spec = {p.name: p for p in penumbra.technique("filtered-sat").parameters}["filter_voxels"]
    assert spec.type == "float" and spec.range[0] <= spec.default <= spec.range[1]
    spp = {p.name: p for p in penumbra.technique("pathtrace").parameters}["spp"]
    assert spp.type == "int" and isinstance(spp.default, int) and spp.range == (1, 1 << 20)
    mode = {p.name: p for p in penumbra.technique("pathtrace").parameters}["mode"]
    assert mode.type == "choice" and mode.default == "single" and "multiple" in mode.range and mode.doc
    renderer = penumbra.Renderer(small_scene(), "pathtrace")
    assert renderer.params["progress"] is False  # Python has the callback; no bar on stderr


def test_progress_is_reported_and_an_exception_from_it_stops_the_render():
    renderer = penumbra.Renderer(small_scene(size=(64, 64)), "pathtrace", spp=256, min_spp=2)
    seen = []
    renderer.render(progress=seen.append)
    assert seen[-1] == 1.0 and seen == sorted(seen)

    class Stop(Exception):
        pass

    def stop(fraction):
        raise Stop()

    slow = penumbra.Renderer(small_scene(size=(64, 64)), "pathtrace", spp=1 << 20, min_spp=2)
    start = time.monotonic()
    with pytest.raises(Stop):
        slow.render(progress=stop)
    assert time.monotonic() - start < 20  # all of 2^20 paths per pixel would take hours
    fast = []
    slow.update(params={"spp": 2})
    assert slow.render(progress=fast.append).shape == (64, 64, 4)  # the renderer still works
    assert fast[-1] == 1.0


def test_ctrl_c_interrupts_a_long_render():
    renderer = penumbra.Renderer(small_scene(size=(64, 64)), "pathtrace", spp=1 << 20, min_spp=2)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        renderer.render()
    assert time.monotonic() - start < 20


def test_the_gil_is_released_while_rendering():
    renderer = penumbra.Renderer(small_scene(size=(64, 64)), "pathtrace", spp=1 << 20, min_spp=2)
    checked = threading.Event()
    outcome = []

    class Stop(Exception):
        pass

    def stop_once_checked(fraction):
        if checked.is_set():
            raise Stop()

    def run():
        try:
            renderer.render(progress=stop_once_checked)
        except Stop:
            outcome.append("stopped")

    worker = threading.Thread(target=run)
    worker.start()
    ticks, deadline = 0, time.monotonic() + 0.5
    while time.monotonic() < deadline:
        ticks += 1
        time.sleep(0.001)
    assert ticks > 50  # this thread kept running while the other one rendered
    with pytest.raises(RuntimeError, match="busy"):
        renderer.update(camera={"eye": [0, -90, 0]})  # one renderer, one thread at a time
    checked.set()
    worker.join(timeout=30)
    assert outcome == ["stopped"] and not worker.is_alive()


def test_threads_setting_is_the_clis_and_images_do_not_depend_on_it():
    scene = small_scene()
    all_threads = penumbra.Renderer(scene, "shadow-rays").render()
    penumbra.set_threads(1)
    try:
        assert penumbra.thread_count() == 1
        renderer = penumbra.Renderer(scene, "shadow-rays")
        assert np.array_equal(renderer.render(), all_threads)
        assert renderer.stats["threads"] == 1
    finally:
        penumbra.set_threads(0)
    with pytest.raises(ValueError, match="threads"):
        penumbra.set_threads(-1)


def test_the_memory_budget_raises_memory_error():
    budget = penumbra.memory_budget()
    penumbra.set_memory_budget(1 << 20)
    try:
        with pytest.raises(MemoryError) as error:
            small_scene(volume={"builtin": "spheres", "size": [256, 256, 256]})
        assert isinstance(error.value, penumbra.MemoryBudgetError) and error.value.bytes > 1 << 20
        with pytest.raises(MemoryError):
            penumbra.Renderer(small_scene(size=(2048, 2048)), "phong").render()
    finally:
        penumbra.set_memory_budget(budget)
