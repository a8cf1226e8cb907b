"""Scenes from dicts, files and keywords; round trips with scene JSON v1; errors."""
import json

import numpy as np
import pytest

import penumbra
from conftest import LIGHT, SOURCE_DIR, TF_POINTS, blob, small_scene

REPOSITORY_SCENES = sorted((SOURCE_DIR / "scenes").glob("*.json"))


def loadable(path):
    """Scenes whose volume and meshes are there (the real volumes live in ../shared/data)."""
    volume = json.loads(path.read_text())["volume"]
    return "builtin" in volume or (path.parent / volume["file"]).exists()


@pytest.mark.parametrize("path", [p for p in REPOSITORY_SCENES if loadable(p)], ids=lambda p: p.name)
def test_repository_scenes_round_trip_through_dicts_and_json(path, tmp_path):
    scene = penumbra.Scene(path)
    d = scene.to_dict()
    assert d["version"] == 1
    again = penumbra.Scene(d, base_dir=path.parent)
    assert again.to_dict() == d
    # The JSON text reads back to the same scene, as the CLI would read it.
    assert penumbra.Scene(json.loads(scene.to_json()), base_dir=path.parent).to_dict() == d
    written = tmp_path / path.name
    penumbra.Scene(d, base_dir=path.parent).save(written)
    assert json.loads(written.read_text()) == json.loads(scene.to_json())


def test_keywords_fill_the_sections():
    scene = small_scene(size=(40, 30), technique="phong", step=0.25, params={"shadow_density_scale": 0.5},
                        lights=LIGHT, background=(0.1, 0.2, 0.3), camera={"eye": [0, -80, 10]})
    d = scene.to_dict()
    assert (d["render"]["width"], d["render"]["height"], d["render"]["technique"]) == (40, 30, "phong")
    assert d["render"]["step"] == 0.25 and d["render"]["params"] == {"shadow_density_scale": 0.5}
    assert d["lights"][0]["type"] == "directional" and len(d["lights"]) == 1
    assert d["background"] == pytest.approx([0.1, 0.2, 0.3])
    assert d["camera"]["eye"] == [0, -80, 10]
    assert [p[4] for p in d["transfer_function"]["points"]] == pytest.approx([p[4] for p in TF_POINTS])
    assert scene.size == (40, 30) and scene["camera"] == d["camera"]


def test_keywords_update_a_scene_file_as_update_does():
    scene = penumbra.Scene(SOURCE_DIR / "scenes" / "spheres.json", size=(40, 30), material={"ambient": 0.3})
    d = scene.to_dict()
    assert (d["render"]["width"], d["render"]["height"], d["render"]["step"]) == (40, 30, 0.5)
    assert d["material"]["ambient"] == pytest.approx(0.3) and d["material"]["shading"] == "phase"
    assert d["camera"]["eye"] == [110, -220, 120]  # the file's camera stays
    assert d["volume"] == {"builtin": "spheres", "size": [96, 96, 96], "time_step": 0}


def test_in_memory_volumes_round_trip_as_data():
    array = blob()
    scene = small_scene(volume=array)
    d = scene.to_dict()
    assert isinstance(d["volume"]["data"], penumbra.Volume) and d["volume"]["time_step"] == 0
    assert np.shares_memory(d["volume"]["data"].to_numpy(), array)
    assert penumbra.Scene(d).to_dict()["camera"] == d["camera"]
    with pytest.raises(penumbra.SceneError, match="in memory"):
        scene.to_json()
    # A volume saved to a file makes a scene the CLI can read.
    assert small_scene(volume={"data": array, "time_step": 0}).volume.dims == (16, 18, 20)


def test_paraview_presets_by_file_and_name(tmp_path):
    presets = [{"Name": "Two", "RGBPoints": [0, 0, 0, 1, 1, 1, 0, 0]},
               {"Name": "Grey", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, 0, 0.5, 0, 1, 0.5, 0.5, 0]}]
    path = tmp_path / "presets.json"
    path.write_text(json.dumps(presets))
    first = small_scene(transfer_function=None, preset=path).to_dict()["transfer_function"]
    grey = small_scene(transfer_function=None, preset=(path, "Grey")).to_dict()["transfer_function"]
    assert first["points"][-1][1:4] == pytest.approx([1.0, 0.0, 0.0])  # "Two" ends red
    assert grey["points"][-1][1:4] == pytest.approx([1.0, 1.0, 1.0]) and grey["points"][-1][4] == pytest.approx(0.5)
    with pytest.raises(OSError, match="Nope"):
        small_scene(transfer_function=None, preset=(path, "Nope"))
    with pytest.raises(penumbra.SceneError):
        small_scene(transfer_function=TF_POINTS, preset=path)


def test_bad_keys_raise_scene_errors_naming_them(tmp_path):
    with pytest.raises(penumbra.SceneError) as error:
        small_scene(lights=[{"type": "directional", "colour": [1, 0, 0]}])
    assert error.value.key == "lights[0].colour" and isinstance(error.value, ValueError)
    with pytest.raises(ValueError, match="render.width"):
        penumbra.Scene(volume={"builtin": "spheres", "size": [8, 8, 8]}, render={"width": "wide"})
    with pytest.raises(penumbra.SceneError, match="colour"):
        small_scene(colour=[1, 0, 0])
    with pytest.raises(penumbra.SceneError, match="volume"):
        penumbra.Scene({"lights": [LIGHT]})
    with pytest.raises(penumbra.SceneError, match="volume.spacing"):
        small_scene(volume={"data": blob(), "spacing": [1, 1, 1]})
    with pytest.raises(ValueError, match="not JSON"):
        small_scene(camera={"eye": object()})
    with pytest.raises(penumbra.SceneError, match="time_step"):
        small_scene(time_step=3)


def test_missing_and_malformed_files_raise_os_errors(tmp_path):
    with pytest.raises(OSError) as error:
        penumbra.Scene(tmp_path / "none.json")
    assert error.value.filename.endswith("none.json")
    (tmp_path / "bad.json").write_text('{"volume": ')
    with pytest.raises(OSError, match="bad.json"):
        penumbra.Scene(tmp_path / "bad.json")
    with pytest.raises(OSError, match="missing.nrrd"):
        penumbra.Scene({"volume": {"file": "missing.nrrd"}}, base_dir=tmp_path)


def test_updates_move_only_the_versions_of_the_parts_that_change():
    scene = small_scene()
    before = scene.versions
    assert scene.update(camera={"eye": [10, -80, 20]}) == ["camera"]
    after = scene.versions
    assert after["camera"] != before["camera"]
    assert {k: v for k, v in after.items() if k != "camera"} == {k: v for k, v in before.items() if k != "camera"}
    # The same sections again, written with their defaults left out, change nothing.
    assert scene.update(camera={"eye": [10, -80, 20]}, lights=[LIGHT], transfer_function=TF_POINTS) == []
    assert scene.versions == after
    assert scene.update(lights=[{"type": "point", "position": [0, 0, 40]}]) == ["lights"]
    assert scene.update(size=(8, 8)) == ["render"]
    assert scene.to_dict()["render"]["technique"] == "shadow-rays"  # render merges: the technique stays
    assert "data" in scene.update(volume={"builtin": "shell", "size": [16, 16, 16]})
    with pytest.raises(penumbra.SceneError):
        scene.update(material={"shading": "toon"})
    assert scene.to_dict()["material"]["shading"] == "phase"  # a bad update changes nothing
