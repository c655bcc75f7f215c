"""Type stubs of the native module ``pdamp._pdamp`` (Rust, PyO3).

Use the typed wrappers in :mod:`pdamp` rather than these functions: they return dataclasses.
Every ``None`` keyword argument means the library's default.
"""

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: Literature exponents of the reference systems: ``logistic_r4_per_iteration`` (ln 2),
#: ``henon_per_iteration`` (0.419217), ``lorenz_per_time`` (0.90563),
#: ``roessler_per_time`` (0.0714).
LYAPUNOV: Dict[str, float]

class SceneError(ValueError):
    """A scene (file, dict or override) that pdamp refuses; the message names the key and the fix."""

class AnalysisError(ValueError):
    """A series or parameter the analysis refuses (too short, non-finite, constant, a time column, …)."""

class SimulationError(RuntimeError):
    """A simulation that could not run to its end (unstable time step, output error, …)."""

_Series = npt.NDArray[np.float64]
_Scene = Union[str, "os.PathLike[str]", Mapping[str, Any]]
_Overrides = Union[Mapping[str, Any], Sequence[str], None]

def mutual_information(
    x: _Series, bins: Optional[int] = None, max_lag: Optional[int] = None
) -> Tuple[_Series, Optional[int], int]:
    """I(τ) for τ = 0..max_lag (nats), its first minimum (or None) and the bins used."""

def false_nearest_neighbors(
    x: _Series,
    m_min: Optional[int] = None,
    m_max: Optional[int] = None,
    tau: Optional[int] = None,
    ratio: Optional[float] = None,
    theiler: Optional[int] = None,
    tisean_vectors: bool = False,
) -> Dict[str, np.ndarray]:
    """Arrays ``m, fraction, accepted, false_count, mean_distance, rms_distance``."""

def kantz(
    x: _Series,
    m_min: Optional[int] = None,
    m_max: Optional[int] = None,
    tau: Optional[int] = None,
    eps_min: Optional[float] = None,
    eps_max: Optional[float] = None,
    eps_count: Optional[int] = None,
    references: Optional[int] = None,
    steps: Optional[int] = None,
    theiler: Optional[int] = None,
    definition_name: Optional[str] = None,
) -> Dict[str, Any]:
    """Curves ``m, eps, s, count, range``, per-curve fits ``fit_*`` and ``exponent`` (JSON
    text, or None with ``exponent_error``)."""

def analyze(
    x: _Series,
    dt: Optional[float] = None,
    forcing_hz: Optional[float] = None,
    max_samples: Optional[int] = None,
    max_lag: Optional[int] = None,
    max_dim: Optional[int] = None,
    fnn_threshold: Optional[float] = None,
    max_fnn_samples: Optional[int] = None,
    kantz_references: Optional[int] = None,
    seed: Optional[int] = None,
) -> str:
    """The analysis report as JSON text, with ``verdict``."""

def simulate(
    scene: _Scene,
    set: _Overrides = None,
    analyze: bool = True,
    series: bool = True,
    out: Optional[str] = None,
) -> Tuple[Dict[str, _Series], Dict[str, np.ndarray], str]:
    """``(series columns, strobe columns, summary JSON text)``."""

def sweep(
    scene: _Scene,
    vary: List[Tuple[str, Union[str, Sequence[Any]]]],
    out: str,
    set: _Overrides = None,
    analyze: bool = True,
) -> Tuple[int, int, int, List[Tuple[int, str]]]:
    """Runs the sweep into ``out``: ``(points, skipped, computed, failed)``."""

def logistic_series(r: float, x0: float, n: int, transient: int = 100) -> _Series:
    """``n`` iterates of ``x ← r x (1 − x)`` from ``x0`` after ``transient`` iterates."""

def henon_x(n: int) -> _Series:
    """x of ``n`` iterates of the Hénon map (1.4, 0.3) after 1000 transient iterates."""

def lorenz_x(n: int, dt: float) -> _Series:
    """x of the Lorenz flow (10, 28, 8/3): ``n`` samples every ``dt`` after 50 time units."""

def roessler_x(n: int, dt: float) -> _Series:
    """x of the Rössler flow (0.2, 0.2, 5.7): ``n`` samples every ``dt``."""
