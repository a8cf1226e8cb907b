"""Rendered images: numpy arrays that show themselves in Jupyter."""
from __future__ import annotations

import os
from typing import Optional

import numpy as np

from . import _penumbra


class Image(np.ndarray):
    """An (H, W, 4) float32 array of linear RGBA, row 0 at the top.

    It is a numpy array in every respect; in Jupyter it displays as the PNG
    that `penumbra render -o x.png` would write (8-bit sRGB, alpha dropped).
    """

    def __new__(cls, array) -> "Image":
        return np.asarray(array, dtype=np.float32).view(cls)

    def _repr_png_(self) -> Optional[bytes]:
        if self.ndim != 3 or self.shape[2] not in (3, 4) or self.size == 0:
            return None  # a slice that is no longer an image: the text repr
        return _penumbra.encode_png(np.asarray(self))

    def to_srgb8(self) -> np.ndarray:
        """The (H, W, 3) uint8 sRGB pixels of the image's PNG."""
        return to_srgb8(self)


def to_srgb8(image) -> np.ndarray:
    """(H, W, 3) uint8 sRGB pixels of a linear image, exactly as the CLI's PNG holds them."""
    return _penumbra.srgb8(np.asarray(image))


def read_image(path: "str | os.PathLike[str]") -> Image:
    """Read a .png (decoded to linear) or .exr image as an Image."""
    return Image(_penumbra.read_image(os.fspath(path)))


def write_image(path: "str | os.PathLike[str]", image) -> None:
    """Write a linear image as .png (8-bit sRGB) or .exr (linear float32 RGBA), as the CLI does."""
    _penumbra.write_image(os.fspath(path), np.asarray(image))
