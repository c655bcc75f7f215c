"""simulate and sweep from Python against the `pdamp` command line's own output.

The CLI writes numbers with Rust's shortest round-trip formatting, so parsing its CSV gives
back the exact doubles: the arrays must be equal, not merely close. The CLI is found through
the environment variable PDAMP_CLI (`.ci/run` sets it; then a missing binary is a failure),
else at target/release/pdamp of the repository (`cargo build --release`); without either,
these comparisons are skipped with that reason.
"""

import contextlib
import csv
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import pdamp

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "data" / "scenes" / "thesis_b_impact.toml"
# a few forcing periods of scene B's impact damper at 15 Hz (e = 0): 20 periods = 1.33 s,
# 13 334 samples at run.sample_interval = 1e-4 s
PERIODS = {"run.periods": 20}


def cli_path():
    env = os.environ.get("PDAMP_CLI")
    if env:
        assert pathlib.Path(env).is_file(), f"PDAMP_CLI={env} does not exist"
        return env
    default = ROOT / "target" / "release" / "pdamp"
    if default.is_file():
        return str(default)
    pytest.skip("no pdamp CLI: run `cargo build --release` or set PDAMP_CLI")


def run_cli(*args):
    subprocess.run([cli_path(), *map(str, args)], check=True, capture_output=True)


def read_csv(path):
    """Columns of a CSV with a header; numbers parsed exactly, empty cells NaN."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    cols = {}
    for j, name in enumerate(rows[0]):
        cells = [r[j] for r in rows[1:]]
        try:
            cols[name] = np.array([float(c) if c else np.nan for c in cells])
        except ValueError:
            cols[name] = np.array(cells, dtype=object)
    return cols


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "run"
    run_cli("simulate", SCENE, "--out", out, "--set", "run.periods=20")
    return out


@pytest.fixture(scope="module")
def py_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("py") / "run"
    return pdamp.simulate(SCENE, set=PERIODS, out=out), out


def test_series_equals_the_cli_csv(cli_run, py_run):
    sim, _ = py_run
    want = read_csv(cli_run / "series.csv")
    assert list(sim.series) == list(want)  # same columns, same order
    assert sim.series["time_s"].size == 13_334
    for name, column in want.items():
        np.testing.assert_array_equal(sim.series[name], column, err_msg=name)
    # the particle impacts: it leaves the floor and the contact code changes
    assert set(np.unique(sim.series["contact"])) >= {0.0, 1.0}


def test_no_ceiling_is_inf_where_the_cli_leaves_the_cell_empty(tmp_path):
    out = tmp_path / "cli"
    run_cli("simulate", SCENE, "--out", out, "--set", "run.periods=4", "--set", "damper.gap=inf",
            "--no-analysis")
    want = read_csv(out / "series.csv")
    sim = pdamp.simulate(SCENE, set={"run.periods": 4, "damper.gap": float("inf")}, analyze=False)
    assert np.all(np.isnan(want["ceiling_z_m"])) and np.all(np.isposinf(sim.series["ceiling_z_m"]))
    for name, column in want.items():
        if name != "ceiling_z_m":
            np.testing.assert_array_equal(sim.series[name], column, err_msg=name)


def test_strobe_and_summary_equal_the_cli(cli_run, py_run):
    sim, _ = py_run
    strobe = read_csv(cli_run / "strobe.csv")
    assert list(sim.strobe) == list(strobe)
    for name, column in strobe.items():
        np.testing.assert_array_equal(sim.strobe[name], column, err_msg=name)
    summary = json.loads((cli_run / "summary.json").read_text())
    assert sim.summary == summary
    # a 20-period record is too short for a verdict, and says how to lengthen it
    assert sim.analysis.regime == "too-short"
    assert "run.periods" in sim.analysis.reason


def test_out_writes_the_cli_run_directory(cli_run, py_run):
    _, out = py_run
    for name in ["series.csv", "strobe.csv", "summary.json", "scene.toml"]:
        assert (out / name).read_bytes() == (cli_run / name).read_bytes(), name


def test_scene_dict_and_overrides_forms_agree():
    if sys.version_info < (3, 11):
        pytest.skip("tomllib needs Python 3.11")
    import tomllib

    table = tomllib.loads(SCENE.read_text())
    a = pdamp.simulate(table, set=["run.periods=6"], analyze=False)
    b = pdamp.simulate(SCENE, set={"run.periods": 6}, analyze=False)
    for name in b.series:
        np.testing.assert_array_equal(a.series[name], b.series[name], err_msg=name)
    assert a.summary == b.summary
    # series=False keeps only the summary, which does not change
    c = pdamp.simulate(SCENE, set={"run.periods": 6}, analyze=False, series=False)
    assert c.series == {} and c.summary == b.summary
    # pandas-friendly
    pd = pytest.importorskip("pandas")
    frame = b.to_pandas()
    assert isinstance(frame, pd.DataFrame) and list(frame.columns) == list(b.series)


def test_bad_scenes_are_refused_naming_the_key(tmp_path):
    with pytest.raises(pdamp.SceneError, match="damper.restitution"):
        pdamp.simulate(SCENE, set={"damper.restitution": 1.5})
    with pytest.raises(pdamp.SceneError, match="--set"):
        pdamp.simulate(SCENE, set=["run.periods"])
    with pytest.raises(TypeError, match="run.periods"):
        pdamp.simulate(SCENE, set={"run.periods": object()})
    with pytest.raises(OSError, match="no_such.toml"):
        pdamp.simulate(tmp_path / "no_such.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[primary\nmass = 1\n")
    with pytest.raises(pdamp.SceneError, match="bad.toml"):
        pdamp.simulate(bad)


def test_sweep_table_equals_the_cli_sweep(tmp_path):
    cli_out = tmp_path / "cli"
    run_cli(
        "sweep", SCENE, "--set", "run.periods=60", "--vary",
        "excitation.frequency=10:18:4", "--no-analysis", "--out", cli_out,
    )
    want = read_csv(cli_out / "sweep.csv")
    sw = pdamp.sweep(
        SCENE, {"excitation.frequency": [10, 14, 18]}, set={"run.periods": 60},
        analyze=False, out=tmp_path / "py",
    )
    assert (sw.points, sw.skipped, sw.computed, sw.failed) == (3, 0, 3, [])
    assert list(sw.table) == list(want)
    for name, column in want.items():
        if column.dtype == object:
            assert list(sw.table[name]) == list(column), name
        else:
            np.testing.assert_array_equal(sw.table[name], column, err_msg=name)
    np.testing.assert_array_equal(sw.table["excitation.frequency"], [10.0, 14.0, 18.0])
    # byte-identical files, and a rerun resumes every point
    assert (tmp_path / "py" / "sweep.csv").read_bytes() == (cli_out / "sweep.csv").read_bytes()
    again = pdamp.sweep(
        SCENE, {"excitation.frequency": "10:18:4"}, set={"run.periods": 60},
        analyze=False, out=tmp_path / "py",
    )
    assert (again.skipped, again.computed) == (3, 0)
    # without out: a temporary directory, same table
    tmp = pdamp.sweep(
        SCENE, {"excitation.frequency": [10, 14, 18]}, set={"run.periods": 60}, analyze=False
    )
    assert tmp.out is None
    np.testing.assert_array_equal(tmp.table["amplitude_m"], want["amplitude_m"])


def test_sweep_refuses_a_bad_range():
    with pytest.raises(pdamp.SceneError, match="excitation.frequency"):
        pdamp.sweep(SCENE, {"excitation.frequency": "10:5:1"}, analyze=False)
    with pytest.raises(pdamp.SceneError, match="empty"):
        pdamp.sweep(SCENE, {"excitation.frequency": []}, analyze=False)


def test_periodic_verdict_of_a_run_reads_as_the_library_writes_it():
    # 10 Hz, e = 0: one impact per cycle, the period-2 orbit of the sweep at 10 Hz (regime
    # column "periodic", period 2); the summary's report has no "verdict" key, the dataclass
    # builds it as the library's AnalysisReport::verdict does ("periodic-2", not "periodic-2.0")
    sim = pdamp.simulate(SCENE, set={"run.periods": 200, "excitation.frequency": 10}, series=False)
    a = sim.analysis
    assert (a.regime, a.period, a.verdict) == ("periodic", 2.0, "periodic-2"), a.reason
    assert sim.strobe["cycle"].size > 0 and sim.series == {}


@contextlib.contextmanager
def ctrl_c(after=0.5, repeat=False):
    """Presses Ctrl-C (SIGINT to this process) `after` seconds into the block (and again every
    `after` seconds with `repeat`); the block must raise KeyboardInterrupt within 5 s."""
    import signal
    import threading
    import time

    done = threading.Event()

    def on_sigint(signum, frame):
        # Ctrl-C's KeyboardInterrupt while the call runs; a press racing its end is ignored
        if not done.is_set():
            raise KeyboardInterrupt

    def press():
        while not done.wait(after):
            os.kill(os.getpid(), signal.SIGINT)
            if not repeat:
                return

    previous = signal.signal(signal.SIGINT, on_sigint)
    start = time.monotonic()
    presser = threading.Thread(target=press, daemon=True)
    presser.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            yield
    finally:
        done.set()
        presser.join()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - start < 5.0


def test_ctrl_c_stops_a_long_run(tmp_path):
    # 2 000 000 forcing periods take ~7 s; SIGINT from 0.5 s on must stop the run within a few
    # periods (checked at the progress reports), not after it ends. The signal is repeated
    # every 0.5 s while the call runs, as a user presses Ctrl-C again (the tests below press
    # once).
    with ctrl_c(repeat=True):
        pdamp.simulate(
            SCENE,
            set={"run.periods": 2_000_000, "run.sample_interval": 1.0},
            analyze=False,
            out=tmp_path / "run",
        )
    # as `pdamp simulate`: the run directory stays marked incomplete, and has no summary
    assert (tmp_path / "run" / "RUNNING").is_file()
    assert not (tmp_path / "run" / "summary.json").exists()


def test_a_first_ctrl_c_stops_a_run_without_samples():
    # one SIGINT, 0.5 s into a run that keeps no samples (series=False, no out): the binding
    # asks Python for pending signals at every progress report (about once per forcing
    # period) and ends the run there. Before, it asked only at the samples, and this run,
    # having none, went on to its end (~7 s) past the Ctrl-C.
    with ctrl_c():
        pdamp.simulate(SCENE, set={"run.periods": 2_000_000}, analyze=False, series=False)


def test_a_first_ctrl_c_stops_a_sweep(tmp_path):
    # one SIGINT, 0.5 s into a sweep of four ~7 s points: the binding watches for signals while
    # the points run on worker threads and asks the sweep to stop; the running points end at
    # their next progress report, the others never start, and no point is written half-done
    with ctrl_c():
        pdamp.sweep(
            SCENE,
            {"excitation.frequency": [10, 12, 14, 16]},
            set={"run.periods": 2_000_000},
            analyze=False,
            out=tmp_path / "sw",
        )
    assert list((tmp_path / "sw" / "points").glob("*.json")) == []
