"""penumbra.Scene: scene JSON v1 (docs/scene-format.md) from a dict, a file or keywords."""
from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _penumbra

# Top-level sections of scene JSON v1 besides "volume" and "version".
SECTIONS = ("transfer_function", "shadow_transfer_function", "camera", "lights", "material", "render", "planes",
            "clip_planes", "background", "meshes")

_PathLike = (str, os.PathLike)


def _volume_section(value: Any) -> Tuple[Optional[dict], Optional[_penumbra.Volume]]:
    """A scene's volume given in any of the accepted forms, as (JSON section, in-memory volume)."""
    if value is None:
        return None, None
    if isinstance(value, _penumbra.Volume):
        return {}, value
    if isinstance(value, np.ndarray):
        return {}, _penumbra.Volume(value)
    if isinstance(value, _PathLike):
        return {"file": os.fspath(value)}, None
    if isinstance(value, dict) and "data" in value:
        section = {k: v for k, v in value.items() if k != "data"}
        data = value["data"]
        return section, data if isinstance(data, _penumbra.Volume) else _penumbra.Volume(np.asarray(data))
    return value, None


def _transfer_function(value: Any, preset: Any) -> Any:
    """A TF given as points, a dict, a preset file or (file, name), as its JSON section."""
    if preset is not None:
        file, name = (preset, None) if isinstance(preset, _PathLike) else tuple(preset)
        section = {"file": os.fspath(file)}
        if name:
            section["name"] = name
        if value is None:
            return {"preset": section}
        if not isinstance(value, dict) or "points" in value:
            raise SceneError("transfer_function", "give points or a preset, not both")
        return {**value, "preset": section}
    if isinstance(value, _PathLike):
        return {"preset": {"file": os.fspath(value)}}
    if isinstance(value, (list, tuple, np.ndarray)):
        return {"points": np.asarray(value, dtype=float).tolist()}
    return value


def SceneError(key: str, message: str) -> _penumbra.SceneError:
    error = _penumbra.SceneError(f"scene key '{key}': {message}")
    error.key = key
    return error


def sections_from_keywords(volume: Any = None, time_step: Optional[int] = None, transfer_function: Any = None,
                           preset: Any = None, size: Optional[Tuple[int, int]] = None,
                           technique: Optional[str] = None, step: Optional[float] = None,
                           params: Optional[Dict[str, Any]] = None,
                           **sections: Any) -> Tuple[Dict[str, Any], Optional[_penumbra.Volume]]:
    """Keyword arguments of Scene(), Scene.update() and Renderer.update() as JSON sections and a volume."""
    unknown = sorted(set(sections) - set(SECTIONS))
    if unknown:
        known = ", ".join(("volume", "time_step", "preset", "size", "technique", "step", "params") + SECTIONS)
        raise SceneError(unknown[0], f"unknown scene section (known: {known})")
    out = {k: v for k, v in sections.items() if v is not None}
    if isinstance(out.get("lights"), dict):
        out["lights"] = [out["lights"]]
    tf = _transfer_function(transfer_function, preset)
    if tf is not None:
        out["transfer_function"] = tf
    if "shadow_transfer_function" in out:
        out["shadow_transfer_function"] = _transfer_function(out["shadow_transfer_function"], None)
    section, memory_volume = _volume_section(volume)
    if time_step is not None:
        section = {**(section or {}), "time_step": int(time_step)}
    if section is not None:
        out["volume"] = section
    render = dict(out.get("render") or {})
    if size is not None:
        render["width"], render["height"] = int(size[0]), int(size[1])
    if technique is not None:
        render["technique"] = technique
    if step is not None:
        render["step"] = step
    if params is not None:
        render["params"] = dict(params)
    if render:
        out["render"] = render
    return out, memory_volume


class Scene:
    """A volume and everything that says how to look at it (scene JSON v1).

    Scene(scene=None, *, base_dir=None, volume=..., transfer_function=..., preset=..., camera=..., lights=...,
          material=..., planes=..., clip_planes=..., background=..., meshes=..., render=...,
          size=(w, h), technique=..., step=..., params={...}, time_step=...)

    scene is a dict in scene JSON v1, the path of a scene file, or another
    Scene; the keywords then update it as update() does (camera, material
    and render merge the keys given). Relative paths resolve against the
    scene file's folder (for a dict: base_dir, default the current folder).

    volume: a penumbra.Volume, a numpy array (wrapped without a copy, see
      Volume), a file path, {"file": ...}, {"builtin": "spheres", "size": [64, 64, 64]},
      or {"data": volume_or_array, "time_step": t}.
    transfer_function: [[value, r, g, b, alpha], ...] (value normalised to the
      range, colours linear), a dict ({"points": ..., "range": [lo, hi] or
      "data", "unit_length": ..., "density_scale": ...}), or a ParaView preset
      file; preset="file.json" or ("file.json", "Cool to Warm") picks one by name.
    lights: a list of (or one) light dicts, e.g. {"type": "directional",
      "direction": [-1, -1, -1]}, {"type": "point", "position": [2, 0, 1]}.
    size, technique, step and params set the render section's width/height,
    technique, step (in voxels) and params.

    Unknown keys and bad values raise SceneError (a ValueError) naming the
    key, e.g. "lights[0].colour"; missing files raise OSError.
    """

    def __init__(self, scene: Any = None, *, base_dir: "str | os.PathLike[str] | None" = None, **keywords: Any):
        sections, memory_volume = sections_from_keywords(**keywords)
        if isinstance(scene, Scene):
            handle = scene._handle.copy()
        elif isinstance(scene, _PathLike):
            handle = _penumbra.SceneHandle.from_file(os.fspath(scene))
        else:
            given = dict(scene or {})
            section, volume = _volume_section(given.pop("volume", None))
            if section is None:  # the volume comes from the keywords
                section, volume, memory_volume = sections.pop("volume", None), memory_volume, None
            if section is None and volume is None:
                raise SceneError("volume", "missing: a scene needs a volume (a Volume, an array, a file or a builtin)")
            given["volume"] = section or {}
            folder = os.fspath(base_dir) if base_dir is not None else os.getcwd()
            handle = _penumbra.SceneHandle(given, folder, volume)
        if sections or memory_volume is not None:
            handle.update(sections, memory_volume)
        self._handle = handle

    @classmethod
    def _wrap(cls, handle: _penumbra.SceneHandle) -> "Scene":
        scene = cls.__new__(cls)
        scene._handle = handle
        return scene

    def update(self, **keywords: Any) -> List[str]:
        """Replace sections (the keywords of Scene()); only the parts that differ change.

        camera, material, render and volume merge the keys given into the
        scene's (a key set to None takes its default); the other sections are
        replaced whole. Returns what changed, as SceneVersions names
        ("camera", "lights", "transfer_function", "data", ...).
        """
        sections, memory_volume = sections_from_keywords(**keywords)
        return self._handle.update(sections, memory_volume)

    def orbit(self, azimuth_deg: float, elevation_deg: float = 0.0) -> None:
        """Turn the camera about its target: azimuth around up, elevation toward it."""
        self._handle.orbit(azimuth_deg, elevation_deg)

    def copy(self) -> "Scene":
        return Scene._wrap(self._handle.copy())

    def to_dict(self) -> Dict[str, Any]:
        """The scene as scene JSON v1, every key written; Scene(scene.to_dict()) is the same scene.

        An in-memory volume appears as {"data": Volume, "time_step": t}.
        """
        d = self._handle.to_json()
        if self._handle.volume_in_memory:
            d["volume"] = {"data": self._handle.volume, **d["volume"]}
        return d

    def to_json(self) -> str:
        """Scene JSON v1 text, as `penumbra` reads it (SceneError for an in-memory volume: save it first)."""
        return self._handle.to_json_text()

    def save(self, path: "str | os.PathLike[str]") -> None:
        """Write the scene as a JSON file (relative paths stay as written)."""
        text = self.to_json()
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

    @property
    def volume(self) -> _penumbra.Volume:
        return self._handle.volume

    @property
    def versions(self) -> Dict[str, int]:
        """The scene's version counters; a part's counter moves whenever that part changes."""
        return self._handle.versions

    @property
    def size(self) -> Tuple[int, int]:
        render = self._handle.to_json()["render"]
        return render["width"], render["height"]

    def __getitem__(self, section: str) -> Any:
        """A section as scene JSON, e.g. scene["camera"]."""
        return self.to_dict()[section]

    def __repr__(self) -> str:
        d = self._handle.to_json()
        r = d["render"]
        source = repr(self.volume) if self._handle.volume_in_memory else d["volume"]
        return f"<penumbra.Scene {source}, {len(d['lights'])} light(s), {r['width']}x{r['height']} {r['technique']}>"
