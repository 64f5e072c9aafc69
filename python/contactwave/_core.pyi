"""Type stubs of the compiled module ``contactwave._core`` (see ``contactwave`` for the
documented public API)."""

from os import PathLike
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class SimulationError(RuntimeError): ...

class Scenario:
    @property
    def file(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def xi(self) -> float: ...
    @property
    def path(self) -> Path: ...
    @property
    def warnings(self) -> List[str]: ...
    def to_json(self) -> str: ...

_Table = Tuple[List[str], npt.NDArray[np.float64], List[Tuple[int, str]]]

def load_scenario(path: Union[str, PathLike[str]]) -> Scenario: ...
def scenario_from_json(text: str, file: str = "<dict>") -> Scenario: ...
def run(scenario: Scenario) -> Dict[str, Any]: ...
def table_json(path: Union[str, PathLike[str]]) -> str: ...
def bench_simulate(scenario: Scenario, n: int) -> List[float]: ...
def law_curve(scenario: Scenario, gap: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
def analyze(
    records: List[np.ndarray], inverse: List[np.ndarray], linear: List[np.ndarray], options: str
) -> Tuple[
    str,
    int,
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]: ...
def fit_power_law(
    pressure: npt.NDArray[np.float64], stiffness: npt.NDArray[np.float64]
) -> Dict[str, float]: ...
def si_value(key: str, value: Union[str, float]) -> float: ...
def quantity(key: str) -> Tuple[str, str]: ...
def identify(
    text: Optional[str],
    path: Union[str, PathLike[str]],
    out: Optional[Union[str, PathLike[str]]] = None,
    design: bool = False,
) -> Tuple[str, str]: ...
def sweep_plan(
    base_json: str, base_path: str, axes: List[Tuple[str, List[float]]]
) -> Tuple[npt.NDArray[np.float64], str, npt.NDArray[np.float64]]: ...
def sweep_local(
    base_json: str,
    base_path: str,
    axes: List[Tuple[str, List[float]]],
    threads: Optional[int] = None,
    progress: Optional[Any] = None,
) -> Tuple[npt.NDArray[np.float64], str, _Table]: ...
def run_points(
    base_json: str, base_path: str, parameters: List[str], points: npt.NDArray[np.float64]
) -> _Table: ...
