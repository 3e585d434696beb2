"""Errors with the CLI's messages, progress, Ctrl-C, threads, and the result type."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import impactlab


def cli_message(cli, *args):
    p = cli(*args, check=False)
    assert p.returncode == 2, p.stderr
    return p.stderr


def test_unknown_version_has_the_clis_message(cli):
    with pytest.raises(impactlab.ParamError) as e:
        impactlab.Model.from_name("A9Z")
    assert str(e.value) in cli_message(cli, "simulate", "--model", "A9Z", "--omega", 1, "--duration", 1, "--out", "/tmp/x.csv")


def test_bad_parameter_file_names_file_and_key(tmp_path, cli):
    bad = tmp_path / "bad.json"
    bad.write_text('{ "base": "A1H", "m": -1 }')
    with pytest.raises(ValueError) as e:
        impactlab.Model.from_json(str(bad))
    assert str(bad) in str(e.value) and "'m'" in str(e.value)
    assert str(e.value) in cli_message(cli, "simulate", "--model", bad, "--omega", 1, "--duration", 1, "--out", tmp_path / "o.csv")
    with pytest.raises(ValueError):
        impactlab.simulate(str(bad), 10, 1)


def test_a_refused_value_leaves_the_model_as_it_was():
    m = impactlab.Model.from_name("A1H")
    with pytest.raises(impactlab.ParamError, match="'m'"):
        m.m = -1
    assert m.m == pytest.approx(6.73766)


def test_refused_arguments_name_the_argument():
    with pytest.raises(ValueError, match="simulate: omega: 2000 is outside"):
        impactlab.simulate("A1H", 2000, 1)
    with pytest.raises(ValueError, match="beyond the bumper"):
        impactlab.simulate("A1H", 10, 1, x0=0.01)
    with pytest.raises(ValueError, match="needs the fixed forcing frequency"):
        impactlab.bifurcation("A1H", over="xI", range=(-0.01, 0.0))
    with pytest.raises(impactlab.ScanError, match="scan: x:"):
        impactlab.scan("A1C", "omega:1:2", "xI:0:0.01:3")
    with pytest.raises(TypeError):
        impactlab.simulate(42, 10, 1)


def test_check_sweep_message_is_the_clis(cli):
    with pytest.raises(ValueError) as e:
        impactlab.bifurcation("A1H", over="xI", range=(-0.5, 0.0), omega=18)
    why = str(e.value).split("bifurcation: ", 1)[1]
    assert why in cli_message(cli, "bifurcation", "--model", "A1H", "--over", "xI", "--range", "-0.5:0", "--omega", 18,
                              "--out", "/tmp/never.csv")


def test_missing_record_names_the_file():
    with pytest.raises(impactlab.DataError, match="/no/such/record.csv"):
        impactlab.fit("/no/such/record.csv", "A1H")


def test_progress_reaches_one_in_order():
    seen = []
    impactlab.bifurcation("A1H", range=(9, 12), steps=40, progress=seen.append)
    assert seen and seen[-1] == 1.0
    assert all(0.0 <= a <= b <= 1.0 for a, b in zip(seen, seen[1:]))


def test_an_exception_in_the_progress_callback_stops_the_run():
    def stop(fraction):
        if fraction > 0:
            raise RuntimeError("enough")

    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        impactlab.bifurcation("A1C", steps=300, progress=stop)
    assert time.monotonic() - t0 < 5


# Calls of several seconds even on a fast machine (each alone: 10 - 100 s of CPU here).
@pytest.mark.parametrize("call", [
    lambda: impactlab.bifurcation("A1C", steps=600, record=400),
    lambda: impactlab.simulate("A1C", 16, 500000, dt=0.5),
    lambda: impactlab.basins("A1G", 13, grid=200, threads=1),
    lambda: impactlab.continue_("A1C", range=(0.5, 25), max_period=16),
])
def test_ctrl_c_stops_a_long_call(call):
    # SIGINT from another thread, as a terminal's Ctrl-C arrives: the call raises KeyboardInterrupt soon after.
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()   # a call that ended first must not leave the signal to hit the test run
    elapsed = time.monotonic() - t0
    assert elapsed < 4.0, f"stopped {elapsed:.1f} s after the start (the signal came at 0.5 s)"
    impactlab.simulate("A1H", 18, 0.5)   # the module works on after an interrupt


def test_long_calls_release_the_gil():
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.005)

    t = threading.Thread(target=count)
    t.start()
    try:
        impactlab.bifurcation("A1H", range=(9, 14), steps=60)
    finally:
        done.set()
        t.join()
    assert len(ticks) > 10


def test_threads_give_the_serial_results():
    serial = [impactlab.simulate("A1H", w, 3)["x"] for w in (12.0, 18.0)]
    results = {}

    def run(w):
        results[w] = impactlab.simulate("A1H", w, 3)["x"]

    threads = [threading.Thread(target=run, args=(w,)) for w in (12.0, 18.0)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results[12.0], serial[0]) and np.array_equal(results[18.0], serial[1])


def test_result_is_a_dict_of_arrays_with_attributes():
    r = impactlab.simulate(impactlab.Model.from_name("A1H"), omega=18, duration=1)
    assert isinstance(r, dict) and isinstance(r["x"], np.ndarray) and len(r["t"]) == len(r["x"])
    assert r.model == "A1H" and r.steps > 0
    with pytest.raises(AttributeError, match="columns: t, x, v, phi, regime"):
        r.nothing
    pandas = pytest.importorskip("pandas")
    assert list(pandas.DataFrame(r).columns) == ["t", "x", "v", "phi", "regime"]


def test_docstrings_and_stubs():
    assert "omega" in impactlab.simulate.__doc__ and "KeyboardInterrupt" in impactlab.simulate.__doc__
    import pathlib
    stub = pathlib.Path(impactlab.__file__).with_name("__init__.pyi")
    assert stub.exists() and "def simulate(" in stub.read_text()
    for name in impactlab.__all__:
        assert name in stub.read_text(), name
