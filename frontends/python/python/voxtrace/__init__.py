"""voxtrace: a CPU voxel ray tracer for Python.

Render the seeded terrain, a MagicaVoxel ``.vox`` file or a ``numpy``
volume of palette indices to an ``(H, W, 4)`` ``uint8`` RGBA image: the
bytes the ``voxtrace`` CLI writes for the same flags, on any number of
threads. Keyword arguments are named as the CLI's flags::

    import voxtrace
    image = voxtrace.render_vox("model.vox", width=960, height=540)
    image.save("model.png")

Errors are ``ValueError`` (a bad argument or file, with the CLI's one-line
message), ``TypeError`` (a volume that is not ``uint8``), ``OSError`` (a
file that cannot be read or written) and ``MemoryError``.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Optional, Sequence, Union

import numpy as np

from . import _voxtrace

__all__ = ["Image", "render", "render_terrain", "render_vox"]

_QUALITIES = {None: 0, "draft": 1, "preview": 1, "standard": 2, "final": 3}
_VIEWS = ["front", "back", "left", "right", "top", "bottom", "iso"]


class Image(np.ndarray):
    """An ``(H, W, 4)`` ``uint8`` RGBA image, rows from the top: a numpy
    array with ``save`` and a notebook preview."""

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes the image to ``path`` as PNG, atomically: the file is
        whole or as it was, never half written."""
        png = self._png()
        target = Path(path)
        folder = target.parent if str(target.parent) else Path(".")
        fd, scratch = tempfile.mkstemp(prefix=f".{target.name}.", dir=folder)
        try:
            # The mode a new file gets (or the old file's), not mkstemp's 0600.
            if target.exists():
                mode = target.stat().st_mode & 0o7777
            else:
                umask = os.umask(0)
                os.umask(umask)
                mode = 0o666 & ~umask
            os.chmod(scratch, mode)
            with os.fdopen(fd, "wb") as file:
                file.write(png)
                file.flush()
                os.fsync(file.fileno())
            os.replace(scratch, target)
        except BaseException:
            if os.path.exists(scratch):
                os.unlink(scratch)
            raise

    def _png(self) -> bytes:
        pixels = np.ascontiguousarray(self, dtype=np.uint8)
        if pixels.ndim != 3 or pixels.shape[2] != 4:
            raise ValueError(f"an image is (H, W, 4), not {pixels.shape}")
        height, width = pixels.shape[:2]
        return _voxtrace.encode_png(width, height, pixels.tobytes())

    def _repr_png_(self) -> bytes:
        """The PNG a notebook shows."""
        return self._png()


def _image(rgba: bytes, width: int, height: int) -> Image:
    return np.frombuffer(rgba, dtype=np.uint8).reshape(height, width, 4).copy().view(Image)


def _vector(name: str, value: Optional[Sequence[float]]) -> Optional[list]:
    if value is None:
        return None
    values = [float(v) for v in value]
    if len(values) != 3:
        raise ValueError(f"{name} is X,Y,Z: three numbers, not {len(values)}")
    return values


def _render(
    scene,
    *,
    width: int,
    height: int,
    position,
    lookat,
    fov,
    orbit,
    view,
    shadows: bool,
    ao: int,
    ao_distance,
    spp,
    fog: bool,
    flat: bool,
    quality,
    threads: int,
) -> Image:
    if quality not in _QUALITIES:
        raise ValueError(f"quality {quality!r} is not 'draft', 'standard' or 'final'")
    if view is not None and view not in _VIEWS:
        raise ValueError(f"view {view!r} is not one of {', '.join(_VIEWS)}")
    if sum(x is not None for x in (position, orbit, view)) > 1:
        raise ValueError("give one of position, orbit and view")
    position, lookat = _vector("position", position), _vector("lookat", lookat)
    turn = [0.0, 0.0, 0.0]
    if orbit is not None:
        turn = [float(v) for v in orbit]
        if len(turn) not in (2, 3):
            raise ValueError(f"orbit is (yaw, pitch) or (yaw, pitch, distance), not {len(turn)} numbers")
        turn += [0.0] * (3 - len(turn))
    aim = 1 if orbit is not None else 2 if view is not None else 0
    if aim == 0 and position is None:
        if lookat is not None or fov is not None:
            raise ValueError("lookat and fov go with a position, orbit or view; give none for the default view")
        position, lookat, fov = scene.default_view(width, height)
    camera = (
        width,
        height,
        aim,
        position if position is not None else [0.0] * 3,
        lookat if lookat is not None else [float("nan")] * 3,
        float(fov) if fov is not None else 0.0,
        turn,
        _VIEWS.index(view) if view is not None else 0,
    )
    effects = (
        bool(shadows),
        int(ao),
        float(ao_distance) if ao_distance is not None else 0.0,
        int(spp) if spp is not None else 0,
        bool(fog),
        bool(flat),
        _QUALITIES[quality],
    )
    return _image(scene.render(camera, effects, int(threads)), width, height)


def render_terrain(
    *,
    seed: int,
    size: int = 100,
    width: int = 1920,
    height: int = 1080,
    position: Optional[Sequence[float]] = None,
    lookat: Optional[Sequence[float]] = None,
    fov: Optional[float] = None,
    orbit: Optional[Sequence[float]] = None,
    view: Optional[str] = None,
    shadows: bool = False,
    ao: int = 0,
    ao_distance: Optional[float] = None,
    spp: Optional[int] = None,
    fog: bool = False,
    flat: bool = False,
    quality: Optional[str] = None,
    threads: int = 0,
    backend: str = "octree",
) -> Image:
    """The seeded terrain over ``[-size, size)^3`` (``--seed``, ``--size``):
    from ``position`` (``--position``), ``orbit`` ``(yaw, pitch[,
    distance])`` (``--orbit``) or ``view`` (``--view``: front, back, left,
    right, top, bottom, iso); with none, from the paper's camera (the
    CLI's default view).
    ``threads`` 0 uses every core, 1 this thread; the bytes are the same."""
    scene = _voxtrace.terrain(size, seed, backend)
    return _render(scene, width=width, height=height, position=position, lookat=lookat,
                   fov=fov, orbit=orbit, view=view, shadows=shadows, ao=ao, ao_distance=ao_distance, spp=spp,
                   fog=fog, flat=flat, quality=quality, threads=threads)


def render_vox(
    path: Union[str, os.PathLike],
    *,
    frame: int = 0,
    width: int = 1920,
    height: int = 1080,
    position: Optional[Sequence[float]] = None,
    lookat: Optional[Sequence[float]] = None,
    fov: Optional[float] = None,
    orbit: Optional[Sequence[float]] = None,
    view: Optional[str] = None,
    shadows: bool = False,
    ao: int = 0,
    ao_distance: Optional[float] = None,
    spp: Optional[int] = None,
    fog: bool = False,
    flat: bool = False,
    quality: Optional[str] = None,
    threads: int = 0,
    backend: str = "octree",
) -> Image:
    """Animation frame ``frame`` of the ``.vox`` file at ``path`` (``--vox``,
    ``--frame``), with its materials, sun and the CLI's default look
    (``quality`` standard for a face-shaded model); the camera as
    ``render_terrain``'s, by default the CLI's measured view (the model's
    front half)."""
    data = Path(path).read_bytes()
    scene = _voxtrace.vox(data, frame, backend)
    return _render(scene, width=width, height=height, position=position, lookat=lookat,
                   fov=fov, orbit=orbit, view=view, shadows=shadows, ao=ao, ao_distance=ao_distance, spp=spp,
                   fog=fog, flat=flat, quality=quality, threads=threads)


def render(
    volume: np.ndarray,
    palette: Optional[np.ndarray] = None,
    *,
    width: int = 1920,
    height: int = 1080,
    position: Optional[Sequence[float]] = None,
    lookat: Optional[Sequence[float]] = None,
    fov: Optional[float] = None,
    orbit: Optional[Sequence[float]] = None,
    view: Optional[str] = None,
    shadows: bool = False,
    ao: int = 0,
    ao_distance: Optional[float] = None,
    spp: Optional[int] = None,
    fog: bool = False,
    flat: bool = False,
    quality: Optional[str] = None,
    threads: int = 0,
    backend: str = "octree",
) -> Image:
    """A ``uint8`` volume indexed ``[x, y, z]`` (y up) of palette indices, 0
    empty, voxel ``(x, y, z)`` filling the cube from ``(x, y, z)`` to
    ``(x+1, y+1, z+1)``. ``palette`` is ``(256, 3)`` or ``(256, 4)``
    ``uint8`` (row 0 unused, alpha ignored); ``None`` gives index ``i`` the
    gray ``(i, i, i)``. The camera as ``render_terrain``'s; by default it
    looks at the volume from its front half as the CLI looks at a model."""
    array = np.asarray(volume)
    if array.dtype != np.uint8:
        raise TypeError(f"a volume is uint8 palette indices, not {array.dtype}")
    if array.ndim != 3:
        raise ValueError(f"a volume is 3-dimensional (x, y, z), not {array.ndim}-dimensional")
    nx, ny, nz = array.shape
    indices = np.asfortranarray(array).tobytes(order="F")
    colors = None
    if palette is not None:
        table = np.asarray(palette)
        if table.dtype != np.uint8:
            raise TypeError(f"a palette is uint8 colors, not {table.dtype}")
        if table.ndim != 2 or table.shape[0] != 256 or table.shape[1] not in (3, 4):
            raise ValueError(f"a palette is (256, 3) or (256, 4), not {table.shape}")
        colors = np.ascontiguousarray(table[1:, :3]).tobytes()
    scene = _voxtrace.voxels(indices, nx, ny, nz, colors, backend)
    return _render(scene, width=width, height=height, position=position, lookat=lookat,
                   fov=fov, orbit=orbit, view=view, shadows=shadows, ao=ao, ao_distance=ao_distance, spp=spp,
                   fog=fog, flat=flat, quality=quality, threads=threads)
