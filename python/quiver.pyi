"""Type stubs for the quiver extension module (docs/PYTHON.md describes each call)."""
import os
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str
KINDS: tuple[str, ...]

Vector = Union[str, Sequence[float], npt.ArrayLike]

class ParseError(ValueError):
    """A scene file's error: the text `quiver render` prints (file:line:column: expected ..., found ...)."""

class UsageError(ValueError):
    """An option the command line would refuse, named by its flag."""

class Scene:
    """A scene built for queries and renders (quiver.load, quiver.from_arrays)."""

    @property
    def name(self) -> str: ...
    @property
    def primitive_count(self) -> int: ...
    @property
    def bounds(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]: ...
    def intersect(
        self,
        origins: npt.ArrayLike,
        directions: npt.ArrayLike,
        tmin: float = 0.0,
        tmax: float = ...,
        threads: int = 0,
        simd: Optional[str] = None,
        *,
        points: bool = False,
    ) -> dict[str, np.ndarray]:
        """Closest hits in (tmin, tmax): t, primitive, kind, instance, u, v, normal (and points)."""
    def occluded(
        self,
        origins: npt.ArrayLike,
        directions: npt.ArrayLike,
        tmin: float = 0.0,
        tmax: float = ...,
        threads: int = 0,
        simd: Optional[str] = None,
    ) -> npt.NDArray[np.bool_]:
        """Whether anything lies in (tmin, tmax) along each ray."""
    def to_toml(self, path: Union[str, os.PathLike[str]]) -> None:
        """Writes a scene made by from_dict as the TOML file the CLI reads to the same scene."""

class Image:
    """An image quiver.render made: its colour and AOVs as NumPy views of it, and save()."""

    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def color(self) -> npt.NDArray[np.float32]: ...
    @property
    def depth(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def normal(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def kind(self) -> Optional[npt.NDArray[np.int32]]: ...
    @property
    def id(self) -> Optional[npt.NDArray[np.int32]]: ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None:
        """Writes the image as `quiver render -o path` would with the same options."""

def load(
    path: Union[str, os.PathLike[str]], crease_angle: Optional[float] = None, *, allow_outside_paths: bool = False
) -> Scene:
    """Reads a scene file (.nff, .toml, .obj, .ply, .gltf, .glb, .stl) and builds it."""

def from_dict(
    scene: dict[str, Any],
    base_dir: Optional[Union[str, os.PathLike[str]]] = None,
    crease_angle: Optional[float] = None,
    *,
    strict: bool = False,
    allow_outside_paths: bool = False,
) -> Scene:
    """A scene from a dict of the TOML scene format's keys, read by the TOML reader itself."""

def from_arrays(
    spheres: Optional[npt.ArrayLike] = None,
    vertices: Optional[npt.ArrayLike] = None,
    triangles: Optional[npt.ArrayLike] = None,
) -> Scene:
    """A scene of spheres (N, 4) and triangles (vertices (V, 3), indices (F, 3))."""

def render(
    scene: Scene,
    *,
    width: Optional[int] = None,
    height: Optional[int] = None,
    aa: Optional[str] = None,
    max_depth: Optional[int] = None,
    min_weight: Optional[float] = None,
    threads: int = 0,
    simd: Optional[str] = None,
    seed: int = 0,
    aov: Optional[str] = None,
    preset: Optional[str] = None,
    two_sided: bool = False,
    robust_methods: bool = False,
    look_from: Optional[Vector] = None,
    look_at: Optional[Vector] = None,
    up: Optional[Vector] = None,
    fov: Optional[float] = None,
    texture_filter: Optional[str] = None,
) -> Image:
    """Renders as `quiver render`: color (H, W, 3) float32 linear and the AOVs asked for."""

def camera_rays(
    scene: Scene,
    *,
    width: Optional[int] = None,
    height: Optional[int] = None,
    look_from: Optional[Vector] = None,
    look_at: Optional[Vector] = None,
    up: Optional[Vector] = None,
    fov: Optional[float] = None,
) -> dict[str, Any]:
    """The primary rays of `quiver trace` in its order: origins, directions, pixels, tile_starts."""

def to_srgb(linear: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """The 8-bit sRGB codes quiver's PNG writer stores for linear values, in the input's shape."""
