"""pdamp — particle (granular) vibration dampers and nonlinear time-series analysis, from Python.

The Rust library pdamp behind a numpy interface:

* analysis of a 1-D series: :func:`mutual_information`, :func:`false_nearest_neighbors`,
  :func:`kantz` (maximal Lyapunov exponent) and :func:`analyze` (the whole chain and the
  regime verdict with its evidence, as ``pdamp analyze``);
* simulation of a scene (a TOML scene file or the same tables as a dict): :func:`simulate`
  (the sampled series as arrays, the stroboscopic points, the summary, as
  ``pdamp simulate``) and :func:`sweep` (a parameter grid as a column table, as
  ``pdamp sweep``);
* the reference systems of the tests: :func:`logistic_series`, :func:`henon_x`,
  :func:`lorenz_x`, :func:`roessler_x` and their literature exponents in :data:`LYAPUNOV`.

Results are dataclasses whose array fields are numpy arrays; tables (``Simulation.series``,
``Sweep.table``) are dicts of equal-length columns, so ``pandas.DataFrame(table)`` (or the
``to_pandas()`` methods) gives a data frame. Units are SI and in the names (``time_s``,
``box_z_m``); exponents are natural-log rates per sample and, with ``dt``, per time unit.

Errors: :class:`SceneError` and :class:`AnalysisError` (both ``ValueError``) name the scene key
or parameter and the fix; :class:`SimulationError` (``RuntimeError``) is a run that could not
finish; ``OSError`` a file that cannot be read or written.

Example::

    import numpy as np, pdamp
    x = pdamp.lorenz_x(20_000, 0.01)
    report = pdamp.analyze(x, dt=0.01)
    print(report.verdict, report.mle_per_time, report.reason)
    sim = pdamp.simulate("data/scenes/thesis_b_impact.toml", set={"run.periods": 20})
    print(sim.series["box_z_m"].max(), sim.summary["amplitude_m"])
"""

from __future__ import annotations

import csv
import json
import os
import tempfile
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _pdamp
from ._pdamp import (
    LYAPUNOV,
    AnalysisError,
    SceneError,
    SimulationError,
    henon_x,
    logistic_series,
    lorenz_x,
    roessler_x,
)

__version__: str = _pdamp.__version__

__all__ = [
    "LYAPUNOV",
    "Analysis",
    "AnalysisError",
    "FalseNearestNeighbors",
    "Kantz",
    "KantzExponent",
    "MutualInformation",
    "SceneError",
    "Simulation",
    "SimulationError",
    "Sweep",
    "analyze",
    "false_nearest_neighbors",
    "henon_x",
    "kantz",
    "logistic_series",
    "lorenz_x",
    "mutual_information",
    "roessler_x",
    "simulate",
    "sweep",
]

#: A scene: the path of a TOML scene file, or its tables as a dict
#: (``{"primary": {...}, "excitation": {...}, "damper": {...}, "run": {...}}``).
SceneLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]
#: Scene overrides: ``{"run.periods": 20, "damper.restitution": 0.8}`` (``None`` as a value
#: removes the key) or the CLI's ``["run.periods=20", "damper.restitution=0.8"]``.
Overrides = Union[Mapping[str, Any], Sequence[str], None]


def _series(x: Any) -> np.ndarray:
    """A 1-D contiguous float64 copy/view of ``x``, or a ``ValueError`` naming the shape."""
    a = np.asarray(x, dtype=np.float64)
    if a.ndim != 1:
        raise ValueError(f"x must be a 1-D array of samples, got an array of shape {a.shape}")
    return np.ascontiguousarray(a)


def _to_pandas(columns: Mapping[str, Any]) -> Any:
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pd.DataFrame(dict(columns))


# ---------------------------------------------------------------- analysis


@dataclass(frozen=True)
class MutualInformation:
    """Time-delayed mutual information I(τ) (Fraser & Swinney 1986; TISEAN ``mutual``).

    Attributes:
        lags: τ = 0..max_lag (samples).
        values: I(τ) in nats; ``values[0]`` is the entropy of the binned series.
        first_minimum: the first local minimum of I(τ) (samples), the usual embedding delay;
            ``None`` when the curve has none up to ``max_lag``.
        bins: histogram bins per axis.
    """

    lags: np.ndarray
    values: np.ndarray
    first_minimum: Optional[int]
    bins: int


def mutual_information(
    x: Any, *, max_lag: Optional[int] = None, bins: Optional[int] = None
) -> MutualInformation:
    """Time-delayed mutual information I(τ), τ = 0..max_lag, of a 1-D series.

    The series is rescaled to [0, 1] and binned in ``bins`` × ``bins`` boxes; I(τ) is summed
    over the N − τ pairs (s[n−τ], s[n]) exactly as TISEAN 3.0.1 ``mutual`` does.

    Args:
        x: the series (any units), 1-D.
        max_lag: largest τ in samples (default 20, TISEAN ``-D``; lowered to N − 1).
        bins: bins per axis (default 16, TISEAN ``-b``).

    Raises:
        AnalysisError: fewer than 2 samples, non-finite or constant samples, a monotonic
            series (a time column), ``bins < 2``.
    """
    values, first_minimum, used_bins = _pdamp.mutual_information(
        _series(x), bins=bins, max_lag=max_lag
    )
    return MutualInformation(
        lags=np.arange(len(values)),
        values=values,
        first_minimum=first_minimum,
        bins=used_bins,
    )


@dataclass(frozen=True)
class FalseNearestNeighbors:
    """False nearest neighbours per embedding dimension (Kennel, Brown & Abarbanel 1992).

    Attributes:
        m: the dimensions tested.
        fraction: fraction of false neighbours per dimension (NaN where no neighbour was
            accepted, i.e. all nearest neighbours farther than σ/ratio).
        accepted: points with an accepted nearest neighbour (the denominator).
        false_count: false neighbours (the numerator).
        mean_distance: mean nearest-neighbour distance of the accepted points (data units).
        rms_distance: root mean square of those distances (data units).
    """

    m: np.ndarray
    fraction: np.ndarray
    accepted: np.ndarray
    false_count: np.ndarray
    mean_distance: np.ndarray
    rms_distance: np.ndarray

    def suggested_dimension(self, threshold: float = 0.05) -> Optional[int]:
        """The first dimension whose false fraction is ≤ ``threshold``, or ``None``."""
        ok = np.flatnonzero(self.fraction <= threshold)
        return int(self.m[ok[0]]) if ok.size else None


def false_nearest_neighbors(
    x: Any,
    *,
    tau: Optional[int] = None,
    m_min: Optional[int] = None,
    m_max: Optional[int] = None,
    ratio: Optional[float] = None,
    theiler: Optional[int] = None,
    tisean: bool = False,
) -> FalseNearestNeighbors:
    """Fraction of false nearest neighbours for m = m_min..m_max.

    A nearest neighbour (maximum norm, |n − j| > theiler) in dimension m is false when the
    next delay coordinate separates the pair by more than ``ratio`` times their distance.

    Args:
        x: the series, 1-D.
        tau: delay in samples (default 1; use the mutual-information minimum).
        m_min: smallest dimension (default 1).
        m_max: largest dimension (default 6, at most 12).
        ratio: escape ratio R_t (default 10, Kennel et al.; TISEAN's default is 2).
        theiler: Theiler window in samples (default: ``tau``).
        tisean: use TISEAN 3.0.1 ``false_nearest``'s univariate vectors (consecutive samples
            whatever ``tau``) instead of delay vectors.

    Raises:
        AnalysisError: a bad parameter (m_min = 0, m_max > 12, tau = 0, ratio ≤ 0), a series
            too short for (m_max + 1)·tau, non-finite, constant or monotonic samples.
    """
    d = _pdamp.false_nearest_neighbors(
        _series(x),
        m_min=m_min,
        m_max=m_max,
        tau=tau,
        ratio=ratio,
        theiler=theiler,
        tisean_vectors=tisean,
    )
    return FalseNearestNeighbors(**d)


@dataclass(frozen=True)
class KantzExponent:
    """The maximal Lyapunov exponent from Kantz's curves: the median slope of their linear
    (scaling) regions.

    Attributes:
        per_sample: exponent per sample (natural log).
        per_time: ``per_sample / dt`` (per time unit of ``dt``), ``None`` without ``dt``.
        m: embedding dimension of the median curve.
        eps: radius of the median curve (data units).
        fit_start: first Δn of its scaling region (samples).
        fit_end: last Δn of its scaling region (samples, inclusive).
        r2: R² of its straight-line fit.
        linear: whether a linear region was found (if not, the slope is a whole-curve
            fallback and should not be trusted).
        curves_used: curves that entered the median.
        spread: max − min of those slopes (per sample).
    """

    per_sample: float
    per_time: Optional[float]
    m: int
    eps: float
    fit_start: int
    fit_end: int
    r2: float
    linear: bool
    curves_used: int
    spread: float


@dataclass(frozen=True)
class Kantz:
    """Kantz's stretching curves S(Δn) for every radius ε and dimension m (Kantz 1994).

    Attributes:
        delta_n: Δn = 0..steps (samples).
        m: dimension of each curve.
        eps: radius of each curve (data units).
        s: S(Δn), one row per curve (rescaled log units; add ``log(range)`` for data units);
            NaN where no reference point had a neighbour.
        count: reference points that contributed, per curve and Δn.
        range: max − min of the series.
        fits: per curve, the scaling region found: ``start``, ``end``, ``slope`` (per
            sample), ``r2`` (NaN: no fit) and ``linear``.
        exponent: the median-slope estimate, ``None`` when no curve has neighbours (then
            ``exponent_error`` says why).
        exponent_error: why there is no estimate.
    """

    delta_n: np.ndarray
    m: np.ndarray
    eps: np.ndarray
    s: np.ndarray
    count: np.ndarray
    range: float
    fits: Dict[str, np.ndarray]
    exponent: Optional[KantzExponent]
    exponent_error: Optional[str] = None


def kantz(
    x: Any,
    *,
    tau: Optional[int] = None,
    m_min: Optional[int] = None,
    m_max: Optional[int] = None,
    eps_min: Optional[float] = None,
    eps_max: Optional[float] = None,
    eps_count: Optional[int] = None,
    steps: Optional[int] = None,
    references: Optional[int] = None,
    theiler: Optional[int] = None,
    definition: str = "mean-distance",
    dt: Optional[float] = None,
) -> Kantz:
    """Kantz's maximal Lyapunov exponent of a series: the curves S(Δn) and their slope.

    S(Δn) is the average over reference points of the log of the mean distance, Δn samples
    later, between the reference's delay vector and those of its neighbours within ε at the
    start. Its slope in the linear region is the exponent per sample.

    Args:
        x: the series, 1-D.
        tau: delay in samples (default 1).
        m_min: smallest dimension (default 2).
        m_max: largest dimension (default 2, at most 16).
        eps_min: smallest radius in data units (default range/1000).
        eps_max: largest radius in data units (default range/100).
        eps_count: radii, log-spaced (default 5).
        steps: largest Δn in samples (default 50).
        references: number of reference points, the first admissible ones (default: all).
        theiler: Theiler window in samples (default: ``tau``; TISEAN ``lyap_k`` uses 0).
        definition: ``"mean-distance"`` (default; Kantz 1994, the mean of the distances) or
            ``"tisean-rms"`` (TISEAN ``lyap_k``, the root-mean-square distance).
        dt: sampling interval; when given, ``exponent.per_time`` is the exponent per time
            unit.

    Raises:
        AnalysisError: a bad parameter, a series shorter than steps + (m_max − 1)·tau,
            non-finite, constant or monotonic samples.
    """
    if dt is not None and not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt}: the sampling interval must be a finite number > 0")
    d = _pdamp.kantz(
        _series(x),
        m_min=m_min,
        m_max=m_max,
        tau=tau,
        eps_min=eps_min,
        eps_max=eps_max,
        eps_count=eps_count,
        references=references,
        steps=steps,
        theiler=theiler,
        definition_name=definition,
    )
    exponent = None
    if d["exponent"] is not None:
        e = json.loads(d["exponent"])
        fit = e["fit"]
        exponent = KantzExponent(
            per_sample=e["per_sample"],
            per_time=None if dt is None else e["per_sample"] / dt,
            m=e["m"],
            eps=e["eps"],
            fit_start=fit["start"],
            fit_end=fit["end"],
            r2=fit["r2"],
            linear=fit["linear"],
            curves_used=e["curves_used"],
            spread=e["spread"],
        )
    return Kantz(
        delta_n=np.arange(d["s"].shape[1]),
        m=d["m"],
        eps=d["eps"],
        s=d["s"],
        count=d["count"],
        range=d["range"],
        fits={
            "start": d["fit_start"],
            "end": d["fit_end"],
            "slope": d["fit_slope"],
            "r2": d["fit_r2"],
            "linear": np.asarray(d["fit_linear"], dtype=bool),
        },
        exponent=exponent,
        exponent_error=d.get("exponent_error"),
    )


@dataclass(frozen=True)
class Analysis:
    """The regime verdict of a series and its evidence (``pdamp analyze --json``).

    Attributes:
        regime: ``"periodic"``, ``"quasi-periodic"``, ``"chaotic"``, ``"irregular"`` (noise-like),
            ``"undetermined"`` or ``"too-short"``.
        verdict: the regime with its period, e.g. ``"periodic-2"``.
        reason: the classifier's rule that fired, in words.
        period: in forcing periods with ``forcing_hz``, else in samples; ``None`` unless
            periodic.
        lag: delay τ chosen (samples).
        embedding_dim: embedding dimension chosen (FNN).
        mle_per_sample: maximal Lyapunov exponent per sample.
        mle_per_time: the same per second (per time unit of ``dt``); ``None`` without ``dt``.
        n_samples: samples analysed (the tail of the series).
        evidence: every quantity given to the classifier (spectral lines, recurrence, FNN,
            Kantz growth, 0–1 test K, surrogate test, …).
        notes: fallbacks taken and estimators that could not run.
        report: the whole report as a dict (the ``analysis`` object of ``summary.json``).
    """

    regime: str
    verdict: str
    reason: str
    period: Optional[float]
    lag: Optional[int]
    embedding_dim: Optional[int]
    mle_per_sample: Optional[float]
    mle_per_time: Optional[float]
    n_samples: int
    evidence: Dict[str, Any]
    notes: List[str]
    report: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_report(cls, report: Mapping[str, Any]) -> "Analysis":
        """An :class:`Analysis` from a report dict (e.g. ``summary["analysis"]``)."""
        r = dict(report)
        regime = r["regime"]
        period = r.get("period")
        verdict = r.get("verdict") or _verdict(regime, period)
        return cls(
            regime=regime,
            verdict=verdict,
            reason=r["reason"],
            period=period,
            lag=r.get("lag"),
            embedding_dim=r.get("embedding_dim"),
            mle_per_sample=r.get("mle_per_sample"),
            mle_per_time=r.get("mle_per_time"),
            n_samples=r["n_samples"],
            evidence=r.get("evidence", {}),
            notes=list(r.get("notes", [])),
            report=r,
        )

    def to_dict(self) -> Dict[str, Any]:
        """The whole report as a dict (JSON-serialisable)."""
        return dict(self.report)


def _verdict(regime: str, period: Optional[float]) -> str:
    """``periodic-p`` with p written as the library writes it (``2``, ``37.3``), else the regime."""
    if regime != "periodic" or period is None:
        return regime
    p = repr(float(period))
    return f"periodic-{p[:-2] if p.endswith('.0') else p}"


def analyze(
    x: Any,
    *,
    dt: Optional[float] = None,
    forcing_hz: Optional[float] = None,
    max_samples: Optional[int] = None,
    max_lag: Optional[int] = None,
    max_dim: Optional[int] = None,
    fnn_threshold: Optional[float] = None,
    max_fnn_samples: Optional[int] = None,
    kantz_references: Optional[int] = None,
    seed: Optional[int] = None,
) -> Analysis:
    """The whole analysis chain on a series and its regime verdict (as ``pdamp analyze``).

    Spectrum and lines, exact recurrence, delay from the mutual information, dimension from
    false nearest neighbours, Kantz's exponent from an ε scan, a stroboscopic section when
    ``forcing_hz`` is given, the 0–1 test and, for autonomous series, a surrogate test of
    nonlinear determinism; then the classifier's verdict.

    Args:
        x: the series, 1-D (feed the steady state, not the transient).
        dt: sampling interval in seconds (default: none; results per sample).
        forcing_hz: forcing frequency in Hz (needs ``dt``): enables the stroboscopic section
            and periods in forcing periods.
        max_samples: only the last ``max_samples`` samples are analysed (default 100 000).
        max_lag: largest lag searched for the MI minimum (default 0 = automatic).
        max_dim: largest FNN dimension (default 8).
        fnn_threshold: FNN fraction accepted (default 0.05).
        max_fnn_samples: FNN uses at most this many samples (default 20 000).
        kantz_references: Kantz reference points (default 2000).
        seed: seed of the 0–1 test and the surrogates (default 1).

    Raises:
        AnalysisError: non-finite samples, a series too short, ``forcing_hz`` without
            ``dt``, ``dt`` ≤ 0. A constant series is not an error (verdict
            ``undetermined`` with a note).
    """
    text = _pdamp.analyze(
        _series(x),
        dt=dt,
        forcing_hz=forcing_hz,
        max_samples=max_samples,
        max_lag=max_lag,
        max_dim=max_dim,
        fnn_threshold=fnn_threshold,
        max_fnn_samples=max_fnn_samples,
        kantz_references=kantz_references,
        seed=seed,
    )
    return Analysis.from_report(json.loads(text))


# ---------------------------------------------------------------- simulation


@dataclass(frozen=True)
class Simulation:
    """One run of a scene (``pdamp simulate``).

    Attributes:
        series: the sampled series, the columns of ``series.csv`` in its order (``time_s``,
            ``base_u_m``, ``box_z_m``, ``box_v_m_s``, ``floor_z_m``, ``ceiling_z_m``,
            ``grain_z_m``, the model's columns, ``grain_force_n``), every
            ``run.sample_interval`` from t = 0; empty with ``series=False``. No NaN: a
            non-finite state stops the run (``SimulationError``); ``ceiling_z_m`` is ``inf``
            without a ceiling (``series.csv`` leaves that cell empty).
        strobe: the exact state once per forcing period over the analysis window (the
            columns of ``strobe.csv``: ``cycle``, ``time_s``, ``grain_z_m``, ``box_z_m``,
            ``grain_v_m_s``, ``box_v_m_s``).
        summary: the run summary (``summary.json``): amplitude, energies per cycle, impacts,
            the analysis report under ``"analysis"`` (or ``"analysis_error"``), ….
    """

    series: Dict[str, np.ndarray]
    strobe: Dict[str, np.ndarray]
    summary: Dict[str, Any]

    @property
    def analysis(self) -> Optional[Analysis]:
        """The regime analysis of the steady state, when it ran."""
        report = self.summary.get("analysis")
        return None if report is None else Analysis.from_report(report)

    def to_pandas(self) -> Any:
        """The series as a ``pandas.DataFrame`` (needs pandas)."""
        return _to_pandas(self.series)


def simulate(
    scene: SceneLike,
    *,
    set: Overrides = None,
    analyze: bool = True,
    series: bool = True,
    out: Union[str, "os.PathLike[str]", None] = None,
) -> Simulation:
    """Run one scene, as ``pdamp simulate SCENE --out OUT [--set …] [--no-analysis]``.

    Args:
        scene: the path of a TOML scene file (``data/scenes/*.toml``) or its tables as a dict.
        set: overrides, ``{"run.periods": 20}`` or ``["run.periods=20"]`` (``run.periods``
            replaces ``run.duration``; ``None`` as a dict value removes a key).
        analyze: run the nonlinear analysis of the steady state (``summary["analysis"]``).
        series: keep the sampled series (``False``: only the summary and strobe, less memory).
        out: also write ``pdamp simulate``'s run directory there (``series.csv``,
            ``summary.json``, ``strobe.csv``, ``scene.toml``).

    Raises:
        SceneError: an invalid scene or override (the message names the key and the fix).
        SimulationError: a run that could not finish (e.g. an unstable DEM time step).
        OSError: a scene file that cannot be read, an ``out`` that cannot be written.
        KeyboardInterrupt: Ctrl-C; a run that records samples stops within a few forcing
            periods (checked at the simulators' progress reports).
    """
    columns, strobe, summary = _pdamp.simulate(
        scene,
        set=set,
        analyze=analyze,
        series=series,
        out=None if out is None else os.fspath(out),
    )
    return Simulation(series=dict(columns), strobe=dict(strobe), summary=json.loads(summary))


@dataclass(frozen=True)
class Sweep:
    """A parameter sweep (``pdamp sweep``): one row per grid point.

    Attributes:
        table: the columns of ``sweep.csv``: the varied keys, then ``frequency_hz``,
            ``amplitude_m``, ``reference_amplitude_m``, energies per cycle, impacts,
            ``regime`` (str), ``period``, exponents, …; numbers as float arrays (NaN for an
            empty cell), text as object arrays.
        points: grid points.
        skipped: points already finished in ``out`` by an earlier run (resumed).
        computed: points computed now.
        failed: ``(point, reason)`` of points that failed (not in the table; a rerun with the
            same ``out`` retries them).
        out: the sweep directory, ``None`` when a temporary one was used.
    """

    table: Dict[str, np.ndarray]
    points: int
    skipped: int
    computed: int
    failed: List[Tuple[int, str]]
    out: Optional[str]

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame`` (needs pandas)."""
        return _to_pandas(self.table)


def sweep(
    scene: SceneLike,
    vary: Mapping[str, Union[str, Sequence[Any], np.ndarray]],
    *,
    set: Overrides = None,
    analyze: bool = True,
    out: Union[str, "os.PathLike[str]", None] = None,
) -> Sweep:
    """Run a parameter grid of a scene in parallel, as ``pdamp sweep … --vary …``.

    Args:
        scene: the path of a TOML scene file or its tables as a dict.
        vary: the varied keys and their values, e.g.
            ``{"excitation.frequency": "10:20:0.5"}`` (``START:STOP:STEP`` or ``"a,b,c"``,
            the CLI's syntax) or ``{"excitation.frequency": [10, 12, 14]}``; several keys
            make a grid, the first varying slowest.
        set: overrides applied to every point (see :func:`simulate`).
        analyze: run the nonlinear analysis of every point (regime, exponents).
        out: the sweep directory (``sweep.csv``, ``strobe.csv``, ``points/``); rerunning the
            same sweep into it resumes. Default: a temporary directory, removed afterwards.

    Raises:
        SceneError: an invalid scene, override or range (checked for every point before any
            runs).
        SimulationError: ``out`` holds a different sweep; file-system errors.

    Points that fail are reported in ``Sweep.failed`` (and with a warning), not raised.
    """
    pairs = [(str(k), v if isinstance(v, str) else _values(v)) for k, v in vary.items()]
    if out is None:
        with tempfile.TemporaryDirectory(prefix="pdamp-sweep-") as tmp:
            return _sweep_into(scene, pairs, set, analyze, tmp, keep=False)
    return _sweep_into(scene, pairs, set, analyze, os.fspath(out), keep=True)


def _values(v: Any) -> List[Any]:
    """Values to sweep as a list of Python scalars (a single value is a list of one)."""
    a = np.asarray(v)
    return [a.item()] if a.ndim == 0 else a.tolist()


def _sweep_into(
    scene: SceneLike,
    pairs: List[Tuple[str, Any]],
    set: Overrides,
    analyze: bool,
    out: str,
    keep: bool,
) -> Sweep:
    points, skipped, computed, failed = _pdamp.sweep(
        scene, pairs, out, set=set, analyze=analyze
    )
    for point, reason in failed:
        warnings.warn(f"sweep point {point} failed: {reason}", RuntimeWarning, stacklevel=3)
    return Sweep(
        table=_read_table(os.path.join(out, "sweep.csv")),
        points=points,
        skipped=skipped,
        computed=computed,
        failed=list(failed),
        out=out if keep else None,
    )


def _read_table(path: str) -> Dict[str, np.ndarray]:
    """A CSV file with a header as columns: float arrays (empty cells NaN) where every cell
    is a number, object arrays of str otherwise."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    table: Dict[str, np.ndarray] = {}
    for j, name in enumerate(header):
        cells = [r[j] if j < len(r) else "" for r in body]
        table[name] = _column(cells)
    return table


def _column(cells: List[str]) -> np.ndarray:
    try:
        return np.array([float(c) if c != "" else np.nan for c in cells], dtype=np.float64)
    except ValueError:
        return np.array(cells, dtype=object)
