"""Type stubs of the compiled engine (`src/lib.rs`); users call the
functions of `voxtrace` itself."""

from typing import Optional, Tuple

Vector = Tuple[float, float, float]

class Scene:
    """A built scene, shared by any number of Python threads."""

    def default_view(self, width: int, height: int) -> Tuple[Vector, Vector, float]:
        """The CLI's camera without camera flags: `(position, lookat, fov)`."""
    def render(
        self,
        camera: Tuple[int, int, int, Vector, Vector, float, Vector, int],
        effects: Tuple[bool, int, float, int, bool, bool, int],
        threads: int,
    ) -> bytes:
        """RGBA bytes of the frame through `camera` (`VtView`'s fields) with
        `effects` (`VtEffects`'), rendered without the GIL."""

def terrain(size: int, seed: int, backend: str) -> Scene:
    """The seeded terrain over `[-size, size)^3`."""

def vox(data: bytes, frame: int, backend: str) -> Scene:
    """Animation frame `frame` of the `.vox` file in `data`."""

def voxels(
    indices: bytes, nx: int, ny: int, nz: int, palette: Optional[bytes], backend: str
) -> Scene:
    """A volume of `nx * ny * nz` palette indices, x fastest; `palette` 765
    RGB bytes or `None`."""

def encode_png(width: int, height: int, rgba: bytes) -> bytes:
    """RGBA bytes as a PNG file's bytes."""

def decode_png(png: bytes) -> Tuple[int, int, bytes]:
    """A PNG file's bytes as `(width, height, rgba)`."""
