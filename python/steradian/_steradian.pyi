"""Types of the compiled extension module (crates/steradian-py)."""

import os
from typing import Any, Callable, Dict, Literal, Optional, Union, final

import numpy as np
import numpy.typing as npt

from steradian import radiometry as radiometry

__all__ = [
    "Measurement",
    "RenderResult",
    "Scene",
    "SceneError",
    "Sums",
    "load_file",
    "load_string",
    "radiometry",
    "read_exr",
    "write_exr",
    "write_png",
]

__version__: str

_Path = Union[str, "os.PathLike[str]"]
_Sensor = Union[int, str]
_Progress = Callable[[int, int], object]

class SceneError(ValueError):
    """A scene that cannot be loaded; ``str(e)`` is ``file:line:col: error: problem``."""

    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    message: str

@final
class Measurement:
    """A sensor reading: value and standard error per RGB channel."""

    @property
    def value(self) -> npt.NDArray[np.float64]: ...
    @property
    def stderr(self) -> npt.NDArray[np.float64]: ...
    @property
    def quantity(self) -> Literal["radiance", "irradiance"]: ...
    @property
    def unit(self) -> str: ...
    @property
    def sensor(self) -> int: ...
    @property
    def spp(self) -> int: ...
    @property
    def dropped_samples(self) -> int: ...
    @property
    def branches(self) -> Optional[int]: ...
    @property
    def target_reached(self) -> bool: ...

@final
class RenderResult:
    """A finished render: the image, each pixel's standard error, what it spent and reached."""

    @property
    def image(self) -> npt.NDArray[np.float32]: ...
    @property
    def stderr(self) -> npt.NDArray[np.float32]: ...
    @property
    def spp(self) -> int: ...
    @property
    def samples(self) -> int: ...
    @property
    def rays(self) -> int: ...
    @property
    def elapsed(self) -> float: ...
    @property
    def error_reached(self) -> float: ...
    @property
    def target_reached(self) -> bool: ...
    @property
    def interrupted(self) -> bool: ...
    @property
    def dropped_samples(self) -> int: ...
    @property
    def branches(self) -> Optional[int]: ...
    @property
    def adaptive(self) -> bool: ...

@final
class Scene:
    """A loaded scene (immutable)."""

    def render(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
        checkpoint: Optional[_Path] = None,
        checkpoint_interval: float = 60.0,
        time_limit: Optional[float] = None,
        target_error: Optional[float] = None,
        allocation: Literal["auto", "adaptive", "uniform"] = "auto",
    ) -> npt.NDArray[np.float32]: ...
    def render_result(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
        checkpoint: Optional[_Path] = None,
        checkpoint_interval: float = 60.0,
        time_limit: Optional[float] = None,
        target_error: Optional[float] = None,
        allocation: Literal["auto", "adaptive", "uniform"] = "auto",
    ) -> RenderResult: ...
    def measure(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
        time_limit: Optional[float] = None,
        target_error: Optional[float] = None,
        batch: Optional[int] = None,
    ) -> Measurement: ...
    def measure_grid(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
        time_limit: Optional[float] = None,
        target_error: Optional[float] = None,
        batch: Optional[int] = None,
    ) -> Dict[str, Any]: ...
    def plan(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
        threads: Optional[int] = None,
    ) -> dict[str, Any]: ...
    def render_range(
        self,
        first: int,
        count: int,
        spp: Optional[int] = None,
        seed: Optional[int] = 0,
        sensor: Optional[_Sensor] = None,
        *,
        quantity: Literal["radiance", "irradiance", "illuminance"] = "radiance",
        branches: Optional[int] = None,
        resume: Optional[Sums] = None,
        scene_digest: int = 0,
        threads: Optional[int] = None,
        progress: Optional[_Progress] = None,
    ) -> Sums: ...
    def develop(self, sums: Sums) -> npt.NDArray[np.float32]: ...
    @property
    def files(self) -> list[str]: ...
    @property
    def sensor_ids(self) -> list[str]: ...
    def film_size(self, sensor: Optional[_Sensor] = None) -> tuple[int, int]: ...
    def channel_names(self, sensor: Optional[_Sensor] = None) -> list[str]: ...

@final
class Sums:
    """The raw float64 sums of samples ``first .. end`` of a render (``Scene.render_range``)."""

    @property
    def first(self) -> int: ...
    @property
    def end(self) -> int: ...
    @property
    def spp(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def branches(self) -> Optional[int]: ...
    @property
    def size(self) -> tuple[int, int]: ...
    @property
    def sensor(self) -> int: ...
    @property
    def quantity(self) -> Literal["radiance", "irradiance", "illuminance"]: ...
    @property
    def scene_digest(self) -> int: ...
    @property
    def dropped_samples(self) -> int: ...
    @property
    def is_prefix(self) -> bool: ...
    @property
    def is_complete(self) -> bool: ...
    def append(self, next: Sums) -> None: ...
    def arrays(self) -> dict[str, npt.NDArray[np.float64]]: ...
    def image(self) -> npt.NDArray[np.float32]: ...
    def stderr(self) -> npt.NDArray[np.float32]: ...
    def to_bytes(self) -> bytes: ...
    @staticmethod
    def from_bytes(data: bytes) -> Sums: ...
    def save(self, path: _Path) -> None: ...
    @staticmethod
    def load(path: _Path) -> Sums: ...

def load_file(path: _Path, **defaults: Any) -> Scene: ...
def load_string(xml: str, /, **defaults: Any) -> Scene: ...
def write_exr(path: _Path, image: npt.ArrayLike) -> None: ...
def read_exr(path: _Path) -> npt.NDArray[np.float32]: ...
def write_png(path: _Path, image: npt.ArrayLike) -> None: ...
