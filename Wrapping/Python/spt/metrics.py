"""Image error measures and small image utilities for comparing renderings.

Images are numpy arrays of shape (h, w, 4) holding premultiplied RGBA, as float in [0, 1] or as
uint8 (converted to float by dividing by 255). Row 0 is the top row of the image.
"""

from __future__ import annotations

import math
import pathlib
from typing import Optional, Sequence, Tuple, Union

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter

PathLike = Union[str, pathlib.Path]


def as_float(image: np.ndarray) -> np.ndarray:
    """Return ``image`` as float64; integer images are divided by 255."""
    image = np.asarray(image)
    if np.issubdtype(image.dtype, np.integer):
        return image.astype(np.float64) / 255.0
    return image.astype(np.float64, copy=False)


def to_uint8(image: np.ndarray) -> np.ndarray:
    """Convert a float image in [0, 1] to uint8 (rounded, clipped); uint8 input is returned
    unchanged."""
    image = np.asarray(image)
    if image.dtype == np.uint8:
        return image
    return np.clip(np.rint(as_float(image) * 255.0), 0, 255).astype(np.uint8)


def _check_pair(a: np.ndarray, b: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Float copies of two same-shaped RGBA images."""
    a, b = as_float(a), as_float(b)
    if a.shape != b.shape or a.ndim != 3 or a.shape[2] != 4:
        raise ValueError(f"expected two RGBA images of equal shape, got {a.shape} and {b.shape}")
    return a, b


def footprint(a: np.ndarray, b: np.ndarray, threshold: float = 1.0 / 255.0) -> np.ndarray:
    """Boolean (h, w) mask of pixels where either image's alpha exceeds ``threshold``."""
    a, b = _check_pair(a, b)
    return (a[..., 3] > threshold) | (b[..., 3] > threshold)


def _masked_diff(a: np.ndarray, b: np.ndarray, mask: Optional[np.ndarray]) -> np.ndarray:
    """Differences a - b of the masked pixels, shape (n, 4)."""
    a, b = _check_pair(a, b)
    if mask is None:
        mask = footprint(a, b)
    mask = np.asarray(mask, dtype=bool)
    if mask.shape != a.shape[:2]:
        raise ValueError(f"mask shape {mask.shape} != image {a.shape[:2]}")
    return (a - b)[mask]


def rmse(a: np.ndarray, b: np.ndarray, mask: Optional[np.ndarray] = None) -> float:
    """Root mean square error over all four channels of the pixels in ``mask`` (default:
    :func:`footprint`). 0.0 for an empty mask."""
    diff = _masked_diff(a, b, mask)
    if diff.size == 0:
        return 0.0
    return float(np.sqrt(np.mean(diff * diff)))


def read_back_floor(reference: np.ndarray) -> float:
    """The RMSE of ``reference`` rounded to 8 bits per channel against itself: the least error
    any image read back through 8 bits per channel can have against it, since rounding to
    the nearest step is each value's least error. Where the values spread over the steps it is
    about 1 / 255 / sqrt(12) = 0.00113."""
    return rmse(as_float(to_uint8(reference)), reference)


def psnr(a: np.ndarray, b: np.ndarray, mask: Optional[np.ndarray] = None) -> float:
    """Peak signal-to-noise ratio in dB with peak 1.0; ``inf`` when the images agree exactly
    on the mask."""
    error = rmse(a, b, mask)
    if error == 0.0:
        return math.inf
    return float(-20.0 * math.log10(error))


def fraction_off(a: np.ndarray, b: np.ndarray, threshold: float = 0.05,
                 mask: Optional[np.ndarray] = None) -> float:
    """Fraction of masked pixels whose largest absolute channel difference exceeds
    ``threshold``. 0.0 for an empty mask."""
    diff = _masked_diff(a, b, mask)
    if diff.shape[0] == 0:
        return 0.0
    return float(np.mean(np.max(np.abs(diff), axis=1) > threshold))


def difference_image(a: np.ndarray, b: np.ndarray, gain: float = 4.0,
                     cmap: str = "inferno") -> np.ndarray:
    """Heat map (h, w, 3) uint8 of the largest absolute RGBA difference per pixel, multiplied
    by ``gain`` and clipped to 1."""
    a, b = _check_pair(a, b)
    values = np.clip(np.max(np.abs(a - b), axis=-1) * gain, 0.0, 1.0)
    try:
        from matplotlib import colormaps
        return to_uint8(colormaps[cmap](values)[..., :3])
    except ImportError:  # grey without matplotlib
        return to_uint8(np.repeat(values[..., None], 3, axis=-1))


def composite_over(image: np.ndarray, background: Sequence[float] = (0.0, 0.0, 0.0)
                   ) -> np.ndarray:
    """Composite a premultiplied RGBA image over an opaque background colour; returns float
    RGB (h, w, 3). RGB input is returned as float."""
    image = as_float(image)
    if image.shape[-1] == 3:
        return image
    back = np.asarray(background, dtype=np.float64)
    return image[..., :3] + (1.0 - image[..., 3:4]) * back


def from_vtk_image(image: vtkImageData, as_float_rgba: bool = False) -> np.ndarray:
    """Convert a 2-D vtkImageData (e.g. from vtkWindowToImageFilter) to an array of shape
    (h, w, components), row 0 at the top: of the image's type (uint8 for window captures), or
    float64 in [0, 1] with ``as_float_rgba``."""
    dims = [0, 0, 0]
    image.GetDimensions(dims)
    scalars = image.GetPointData().GetScalars()
    if scalars is None:
        raise ValueError("image has no point scalars")
    pixels = vtk_to_numpy(scalars).reshape(dims[1], dims[0], scalars.GetNumberOfComponents())
    pixels = np.ascontiguousarray(pixels[::-1])
    return as_float(pixels) if as_float_rgba else pixels


def to_vtk_image(array: np.ndarray) -> vtkImageData:
    """Convert an (h, w), (h, w, 3) or (h, w, 4) array (row 0 at the top) to a uint8
    vtkImageData (row 0 at the bottom, VTK convention)."""
    pixels = to_uint8(array)
    if pixels.ndim == 2:
        pixels = pixels[..., None]
    if pixels.ndim != 3 or pixels.shape[2] not in (1, 2, 3, 4):
        raise ValueError(f"unsupported image shape {pixels.shape}")
    height, width, components = pixels.shape
    flat = np.ascontiguousarray(pixels[::-1]).reshape(-1, components)
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    scalars = numpy_to_vtk(flat, deep=True)
    scalars.SetName("pixels")
    image.GetPointData().SetScalars(scalars)
    return image


def write_png(path: PathLike, array: np.ndarray) -> None:
    """Write a grey, RGB or RGBA image (uint8 or float in [0, 1], row 0 at the top) to a PNG
    file. RGBA is written as stored (premultiplied data is not un-premultiplied; see
    :func:`composite_over`)."""
    writer = vtkPNGWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(to_vtk_image(array))
    writer.Write()
    if writer.GetErrorCode():
        raise OSError(f"could not write PNG {path}")


def _label_strip(text: str, width: int, height: int, background: float) -> np.ndarray:
    """``text`` centred in a (height, width, 3) uint8 strip drawn by matplotlib's Agg canvas;
    a plain strip without matplotlib."""
    shade = to_uint8(np.full((height, width, 3), background))
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        return shade
    dpi = 100.0
    figure = Figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    figure.patch.set_facecolor((background,) * 3)
    figure.text(0.5, 0.5, text, ha="center", va="center", color="white",
                fontsize=max(6.0, 0.45 * height * 72.0 / dpi))
    canvas = FigureCanvasAgg(figure)
    canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())
    strip = shade.copy()
    h, w = min(height, rgba.shape[0]), min(width, rgba.shape[1])
    strip[:h, :w] = rgba[:h, :w, :3]
    return strip


def _to_rgb8(image: np.ndarray, background: float) -> np.ndarray:
    """Grey, RGB or premultiplied RGBA image -> uint8 RGB over a grey background."""
    image = as_float(image)
    if image.ndim == 2:
        image = image[..., None]
    if image.shape[-1] == 1:
        return to_uint8(np.repeat(image, 3, axis=-1))
    return to_uint8(composite_over(image, (background,) * 3))


def side_by_side(images: Sequence[np.ndarray], labels: Optional[Sequence[str]] = None,
                 gap: int = 8, label_height: int = 28, background: float = 0.12) -> np.ndarray:
    """Compose images left to right on a dark background, each with an optional label above
    it. RGBA images are composited over the background. Returns a uint8 RGB array."""
    if not images:
        raise ValueError("no images given")
    if labels is not None and len(labels) != len(images):
        raise ValueError("need one label per image")
    rgb = [_to_rgb8(img, background) for img in images]
    top = label_height if labels is not None else 0
    height = max(img.shape[0] for img in rgb) + top + 2 * gap
    width = sum(img.shape[1] for img in rgb) + gap * (len(rgb) + 1)
    canvas = to_uint8(np.full((height, width, 3), background))
    x = gap
    for index, img in enumerate(rgb):
        h, w = img.shape[:2]
        if labels is not None:
            canvas[gap:gap + top, x:x + w] = _label_strip(labels[index], w, top, background)
        canvas[gap + top:gap + top + h, x:x + w] = img
        x += w + gap
    return canvas
