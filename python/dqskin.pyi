"""Type stubs of the dqskin module (python/, docs/python.md): what editors complete and check."""
from types import SimpleNamespace
from os import PathLike
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

class Error(Exception):
    """Any error dqskin reports."""

class InputError(Error, ValueError):
    """A file or an argument dqskin refuses: the command line's one-line message."""

class OutputError(Error, OSError):
    """A file dqskin cannot write."""

class NoGpuContext(Error, RuntimeError):
    """No GL context for the backend asked (egl, osmesa)."""

class Warning(UserWarning):
    """A warning the command printed (bake, diff, lint, report), passed to the warnings module."""

class Clip(SimpleNamespace):
    """An animation: a SimpleNamespace with these attributes."""
    index: int
    name: str
    duration: float
    key_times: npt.NDArray[np.float64]

class Scene(SimpleNamespace):
    index: int
    name: str

class Skin(SimpleNamespace):
    index: int
    name: str
    joints: list[str]

class Frames(SimpleNamespace):
    """What Asset.deform returns."""
    times: npt.NDArray[np.float64]
    positions: npt.NDArray[np.float32]            # frames x vertices x 3
    normals: Optional[npt.NDArray[np.float32]]    # frames x vertices x 3, or None
    tangents: Optional[npt.NDArray[np.float32]]   # frames x vertices x 4, or None

class Asset:
    """A loaded glTF file: its scenes, skins and clips, ready to deform."""
    @property
    def path(self) -> str: ...
    @property
    def scene(self) -> int: ...
    @property
    def scenes(self) -> list[Scene]: ...
    @property
    def skins(self) -> list[Skin]: ...
    @property
    def clips(self) -> list[Clip]: ...
    @property
    def vertices(self) -> int: ...
    def clip(self, which: Union[int, str]) -> Clip: ...
    def deform(self, clip: Union[Clip, str, int, None], times: Union[Sequence[float], npt.ArrayLike],
               mode: str = "dqs", backend: str = "auto") -> Frames: ...

def load(path: str, resource_root: Union[str, Sequence[str], None] = None,
         max_memory: Union[int, str, None] = None) -> Asset: ...

_Path = Union[str, PathLike[str]]
_Paths = Union[_Path, Sequence[_Path]]
# The commands: their options as `dqskin COMMAND --help` lists them, as keyword arguments (dashes as
# underscores; flags True or False; a list for several values or a comma-separated one).

def bake(inputs: _Paths, **options: Any) -> dict[str, Any]: ...
def report(inputs: _Paths, **options: Any) -> dict[str, Any]: ...
def diff(a: _Path, b: _Path, **options: Any) -> dict[str, Any]: ...
def lint(inputs: _Paths, **options: Any) -> dict[str, Any]: ...
