"""Type stubs of the native module (the public API is in ``fiberfold/__init__.py``)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

class SolverError(RuntimeError):
    result: Any

class Parameters:
    """Table 1's parameters (lengths in H, moduli in mu_s, beta in radians); keyword overrides
    are validated (``ValueError`` naming the parameter and range, ``TypeError`` for a wrong
    type). Laws by dotted keys, ``Parameters(**{"layer.law": "ogden", "layer.alpha": -25})``,
    or a table, ``Parameters(layer={"law": "ogden", "alpha": -25})``; ``to_dict()`` lists
    them as dotted keys."""

    mu_l: float
    K_l: float
    mu_s: float
    K_s: float
    phi_m: float
    phi_f: float
    mu_f: float
    lambda_f: float
    beta: float
    psi: float
    tension_only: bool
    incompressible: bool
    growth_layer: float
    growth_substrate: float
    area_growth: bool
    load: str
    def __init__(self, **overrides: Union[float, int, bool, str, List[float], Dict[str, Any]]) -> None: ...
    @staticmethod
    def from_toml(path: Union[str, PathLike[str]]) -> Parameters: ...
    def to_toml(self) -> str: ...
    def replace(self, **overrides: Union[float, int, bool, str, List[float], Dict[str, Any]]) -> Parameters: ...
    def to_dict(self) -> Dict[str, Union[float, bool, str, List[float]]]: ...

class State:
    @property
    def points(self) -> npt.NDArray[np.float64]: ...
    @property
    def deformed_points(self) -> npt.NDArray[np.float64]: ...
    @property
    def cells(self) -> npt.NDArray[np.int64]: ...
    @property
    def point_data(self) -> Dict[str, npt.NDArray[np.float64]]: ...
    @property
    def cell_data(self) -> Dict[str, npt.NDArray[np.float64]]: ...
    def write_vtu(self, path: Union[str, PathLike[str]]) -> None: ...

def homogeneous(params: Parameters, d: npt.ArrayLike) -> Dict[str, npt.NDArray[np.float64]]: ...
def dispersion(
    params: Parameters,
    k: npt.ArrayLike,
    method_name: str = ...,
    biaxial: Optional[float] = ...,
    theta: Optional[float] = ...,
) -> Dict[str, npt.NDArray[np.float64]]: ...
def onset(
    params: Parameters, method_name: str = ..., biaxial: Optional[float] = ..., theta: Optional[float] = ...
) -> str: ...
def sweep(
    params: Parameters,
    name: str,
    values: npt.ArrayLike,
    series: Optional[Tuple[str, List[float]]] = ...,
    method_name: str = ...,
    biaxial: Optional[float] = ...,
    theta: Optional[float] = ...,
) -> Dict[str, npt.NDArray[np.float64]]: ...
def simulate_run(
    params: Parameters,
    options: str,
    progress: Optional[Callable[[Dict[str, Any]], None]],
    out: Optional[str] = ...,
) -> Tuple[Dict[str, npt.NDArray[np.float64]], str, State, Optional[str]]: ...
def simulate_defaults() -> str: ...
def bifurcation_run(params: Parameters, out: str, mesh: str = ..., element: Optional[str] = ...) -> str: ...
def pattern_run(
    params: Parameters,
    out: str,
    biaxial: float = ...,
    periods: int = ...,
    elements_per_wavelength: int = ...,
    follow_to: Optional[float] = ...,
    imperfection: float = ...,
    follow_past: Optional[float] = ...,
    resume: bool = ...,
    max_side: float = ...,
) -> str: ...
def crease_run(params: Parameters, options: str) -> str: ...
def crease_defaults() -> str: ...
