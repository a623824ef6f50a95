# Type stubs of the package mb_kinematics (doc/python.md): its public names, as __all__ lists
# them. test/python/test_typing.py checks them against the module (mypy's stubtest).
import os
from typing import (Any, Dict, Final, Iterable, Iterator, Mapping, Optional, Sequence, Tuple,
                    Union)

import numpy as np
import numpy.typing as npt

__all__: list[str]
__version__: str

#: Every output Model.kinematics can write, in its order.
OUTPUTS: Tuple[str, ...]
#: Written only when asked for by name (partial velocities, segment frames, joint motion).
OPT_IN: Tuple[str, ...]

_Array = npt.NDArray[np.float64]
_Values = Union[npt.ArrayLike, Mapping[str, npt.ArrayLike]]

def load(path_or_text: Union[str, os.PathLike[str]], scale: Optional[float] = ...,
         body_mass: Optional[float] = ..., sex: Optional[str] = ...,
         segments: Union[None, str, os.PathLike[str]] = ...,
         anthropometry: Optional[str] = ...) -> Model: ...

def angles(rotation: npt.ArrayLike, order: Union[str, Sequence[str]]) -> _Array: ...

def release_memory() -> int: ...

class Recording:
    def __init__(self, core: Any, source: Any) -> None: ...
    @property
    def times(self) -> _Array: ...
    @property
    def positions(self) -> _Array: ...
    @property
    def velocities(self) -> _Array: ...
    @property
    def accelerations(self) -> _Array: ...
    @property
    def grid(self) -> Dict[str, Any]: ...
    @property
    def drops(self) -> Dict[str, int]: ...
    @property
    def base(self) -> Optional[Dict[str, Any]]: ...
    def __len__(self) -> int: ...

class Model:
    # Set by __init__, read-only (Model.__setattr__ refuses them).
    frame: Final[str]
    nq: Final[int]
    nv: Final[int]
    coordinate_names: Final[Tuple[str, ...]]
    speed_names: Final[Tuple[str, ...]]
    body_names: Final[Tuple[str, ...]]
    joint_names: Final[Tuple[str, ...]]
    joint_types: Final[Tuple[str, ...]]
    masses: Final[_Array]
    mass_centers: Final[_Array]
    lower: Final[npt.NDArray[np.int64]]
    mimics: Final[Tuple[Dict[str, Any], ...]]
    warnings: Final[Tuple[str, ...]]
    neutral_position: Final[_Array]
    scale: Final[float]
    def __init__(self, core: Any, scale: float = ...) -> None: ...
    @property
    def body_count(self) -> int: ...
    @property
    def root(self) -> Dict[str, Any]: ...
    @property
    def lower_table(self) -> npt.NDArray[np.int64]: ...
    def tables(self) -> str: ...
    def body_index(self, name: str) -> int: ...
    def read_recording(self, path: Union[str, os.PathLike[str]], scale: Optional[float] = ...,
                       joint_states: str = ..., joint_accelerations: Optional[str] = ...,
                       base_odometry: Optional[str] = ...) -> Recording: ...
    def recording(self, times: npt.ArrayLike, positions: npt.ArrayLike) -> Recording: ...
    def states(self, recording: Recording, estimator: str = ...,
               max_gap: Optional[float] = ...) -> Dict[str, Any]: ...
    def recording_kinematics(self, recording: Recording, estimator: str = ...,
                             max_gap: Optional[float] = ..., **options: Any) -> Dict[str, Any]: ...
    def kinematics(self, q: _Values, velocity: Optional[_Values] = ...,
                   acceleration: Optional[_Values] = ...,
                   outputs: Union[None, str, Iterable[str]] = ...,
                   bodies: Union[None, str, int, Sequence[Union[str, int]]] = ...,
                   threads: Optional[int] = ...,
                   out: Optional[Dict[str, npt.NDArray[Any]]] = ...,
                   dtype: npt.DTypeLike = ...) -> Dict[str, npt.NDArray[Any]]: ...
    def kinematics_chunks(self, q: _Values, velocity: Optional[_Values] = ...,
                          acceleration: Optional[_Values] = ..., rows: int = ...,
                          out: Optional[Dict[str, npt.NDArray[Any]]] = ...,
                          **options: Any) -> Iterator[Tuple[int, Dict[str, npt.NDArray[Any]]]]: ...
