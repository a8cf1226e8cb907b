"""penumbra.Renderer and penumbra.compare: techniques over scenes."""
from __future__ import annotations

import warnings
from typing import Any, Callable, Dict, Iterable, List, Optional

import numpy as np

from . import _penumbra
from .image import Image
from .scene import Scene, sections_from_keywords

ProgressCallback = Callable[[float], Any]


class Renderer:
    """One technique rendering one scene, keeping its structures between renders.

    Renderer(scene, technique=None, **params)

    scene is a Scene (or anything Scene() accepts; the renderer keeps its own
    copy). technique defaults to the scene's render.technique; params are the
    technique's parameters (penumbra.technique(name).parameters), over the
    scene's render.params, and raise ParameterError (a ValueError) naming a
    parameter that is unknown or out of range.

    update() changes the camera, lights, TF, parameters ... and the next
    render() rebuilds only what depends on what changed: a camera move
    rebuilds no light-space structure (the scene's version counters decide, as
    in the server). stats holds the timings `penumbra bench` reports.

    render() lets go of the GIL and runs on the thread pool set by
    penumbra.set_threads() (the CLI's --threads). Ctrl-C stops it
    (KeyboardInterrupt): pathtrace stops within a pass; other techniques,
    whose frames are short, finish theirs first.
    """

    def __init__(self, scene: Any, technique: Optional[str] = None, **params: Any):
        if not isinstance(scene, Scene):
            scene = Scene(scene)
        self._handle = _penumbra.RendererHandle(scene._handle, technique or "", params)
        meshes = scene._handle.to_json().get("meshes")
        if meshes and not _penumbra.technique(self.technique).draws_meshes:
            warnings.warn(f"{self.technique} does not draw the scene's {len(meshes)} mesh(es); "
                          + ", ".join(sorted(t.name for t in _penumbra.techniques() if t.draws_meshes)) + " do",
                          stacklevel=2)

    def render(self, progress: Optional[ProgressCallback] = None) -> Image:
        """The scene as an (H, W, 4) float32 linear RGBA Image (alpha: the accumulated opacity).

        progress(fraction) is called about every 0.1 s from this thread while
        the frame renders (pathtrace reports its fraction; the others 0) and
        with 1.0 at the end; an exception it raises stops the render and
        propagates.
        """
        return Image(self._handle.render(progress))

    def render_srgb(self, progress: Optional[ProgressCallback] = None) -> np.ndarray:
        """The scene as (H, W, 3) uint8 sRGB, the pixels of the CLI's PNG."""
        return self._handle.render_srgb(progress)

    def update(self, *, params: Optional[Dict[str, Any]] = None, **sections: Any) -> List[str]:
        """Change scene sections (the keywords of Scene()) and technique parameters.

        camera, material, render and volume merge the keys given; the other
        sections are replaced whole. params={"name": value} sets parameters
        (None restores the scene's value or the default). Nothing changes when
        anything is invalid. Returns what changed ("camera", "lights",
        "transfer_function", "data", "params", ...); the next render() or
        prepare() rebuilds only what depends on it.
        """
        scene_sections, volume = sections_from_keywords(**sections)
        return self._handle.update(scene_sections, volume, dict(params or {}))

    def orbit(self, azimuth_deg: float, elevation_deg: float = 0.0) -> List[str]:
        """Turn the camera about its target (degrees): azimuth around up, elevation toward it."""
        return self._handle.orbit(azimuth_deg, elevation_deg)

    def prepare(self) -> None:
        """Bring the technique's structures up to date now (render() does it too); timed in stats."""
        self._handle.prepare()

    def standard_error(self) -> Optional[Image]:
        """For pathtrace, after a render: per pixel the standard error of the mean (rgb) and the paths taken (alpha)."""
        e = self._handle.standard_error()
        return None if e is None else Image(e)

    @property
    def stats(self) -> Dict[str, Any]:
        """Timings and costs, as `penumbra bench` names them.

        build_ms: the first prepare (every structure built); prepare_ms,
        render_ms, frame_ms (prepare + render) of the last render();
        tf_change_ms / light_move_ms: the last prepare after an update that
        changed only the TF / only the lights (None before one); aux_bytes:
        the technique's own memory; rebuilds: how often it rebuilt its
        structures; samples, rays, passes of the last render; renders; threads.
        """
        return self._handle.stats

    @property
    def technique(self) -> str:
        return self._handle.technique

    @property
    def params(self) -> Dict[str, Any]:
        """Every parameter of the technique with the value renders use."""
        return self._handle.params

    @property
    def scene(self) -> Scene:
        """A copy of the scene as the renderer has it now."""
        return Scene._wrap(self._handle.scene)

    def __repr__(self) -> str:
        return f"<penumbra.Renderer {self.technique} {self.scene!r}>"


def compare(scene: Any, techniques: Iterable[str], reference: str = "pathtrace", *,
            reference_image: Any = None, params: Optional[Dict[str, Any]] = None, frames: int = 3,
            progress: Optional[ProgressCallback] = None) -> Dict[str, Any]:
    """Render the scene with each technique and measure it against a reference, as `penumbra compare`.

    techniques: names, or "all" for every technique but the reference.
    reference: the technique that renders the reference, unless
    reference_image (an (H, W, 3|4) linear array of the scene's size) is given.
    params: {"technique": {"name": value}} for one technique, {"name": value}
    for every technique that declares it.

    Returns report.json as a dict ("reference", "techniques": per technique
    rmse, psnr, ssim, mean_de, p99_de, max_de, tf_change_ms, light_move_ms,
    frame_ms, aux_bytes, params) plus "images" (name -> Image, and
    "reference"), "delta_e" (name -> (H, W) CIEDE2000 against the reference)
    and, for a pathtrace reference, "reference_noise_de" and
    "reference_standard_error".
    """
    if not isinstance(scene, Scene):
        scene = Scene(scene)
    names = [techniques] if isinstance(techniques, str) else list(techniques)
    if names == ["all"]:
        names = [t.name for t in _penumbra.techniques() if t.name != reference]
    result = _penumbra.compare(scene._handle, names, reference, reference_image, dict(params or {}), frames,
                               progress)
    result["images"] = {name: Image(image) for name, image in result["images"].items()}
    if "reference_standard_error" in result:
        result["reference_standard_error"] = Image(result["reference_standard_error"])
    return result
