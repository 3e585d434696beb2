"""Each function of the module against the CLI on the same inputs: the same numbers as its CSVs print them
(bit for bit where the CLI prints full precision: scan)."""
import json
import re

import numpy as np
import pytest

import impactlab
from conftest import assert_columns_match, read_csv


def test_models_and_model_attributes():
    names = impactlab.models()
    assert names[:5] == ["A1C", "A1C1", "A3C", "A1G", "A1H"]
    m = impactlab.Model.from_name("A1H")
    assert (m.name, m.stiffness, m.impact, m.rigid) == ("A1H", "A1", "H", True)
    assert m.m == pytest.approx(6.73766) and m.xI == 0.0
    assert "[kg]" in impactlab.Model.m.__doc__
    assert set(m.impact_params) >= {"kappa0", "Ti0"}
    c = impactlab.Model.from_name("A1C")
    assert c["kI"] == pytest.approx(2.3983e8)
    c["kI"] = 1e9
    assert c["kI"] == 1e9 and impactlab.Model.from_name("A1C")["kI"] == pytest.approx(2.3983e8)
    assert "constant_force" in impactlab.effects()


def test_model_json_round_trip(tmp_path, cli):
    m = impactlab.Model.from_name("A1G")
    m.xI = -0.004
    m.m0e = 0.03
    path = tmp_path / "m.json"
    m.save(path)                         # a pathlib.Path or a str
    back = impactlab.Model.from_json(path)
    assert back == m and back.xI == -0.004
    # The CLI reads the file the module wrote, and the module the file the CLI writes.
    text = cli("models", "--json", "A3C1").stdout
    assert impactlab.Model.from_json_text(text) == impactlab.Model.from_name("A3C1")


def test_simulate(tmp_path, cli):
    out = tmp_path / "traj.csv"
    cli("simulate", "--model", "A1H", "--omega", 18, "--duration", 5, "--out", out)
    r = impactlab.simulate(impactlab.Model.from_name("A1H"), omega=18, duration=5)
    assert list(r) == ["t", "x", "v", "phi", "regime"]
    assert_columns_match(r, out)
    assert r.impacts > 0 and r["regime"].dtype.kind == "i"


def test_simulate_from_a_parameter_file_and_a_start(tmp_path, cli):
    m = impactlab.Model.from_name("A1C")
    m.xI = 0.004
    m.save(str(tmp_path / "m.json"))
    out = tmp_path / "traj.csv"
    cli("simulate", "--model", tmp_path / "m.json", "--omega", 12.5, "--duration", 3, "--dt", 0.002, "--x0", -0.01,
        "--v0", 0.05, "--rtol", 1e-9, "--out", out)
    r = impactlab.simulate(tmp_path / "m.json", 12.5, 3, dt=0.002, x0=-0.01, v0=0.05, rtol=1e-9)
    assert_columns_match(r, out)


def test_simulate_driven_by_a_recorded_input(tmp_path, cli):
    t = np.arange(2001) * 1e-3
    with open(tmp_path / "rec.csv", "w") as f:
        f.write("t,x,u\n")
        for ti in t:
            f.write(f"{ti:.6f},0,{5 * np.sin(2 * np.pi * 3 * ti):.9f}\n")
    m = impactlab.Model.from_name("A1C")
    m.input_gain = 2.0
    m.m0e = 0.0
    m.save(tmp_path / "m.json")
    out = tmp_path / "traj.csv"
    cli("simulate", "--model", tmp_path / "m.json", "--input", tmp_path / "rec.csv", "--out", out)
    r = impactlab.simulate(tmp_path / "m.json", input=tmp_path / "rec.csv")
    assert list(r) == ["t", "x", "v", "u", "regime"] and len(r["t"]) == 2001
    assert_columns_match(r, out)
    assert np.ptp(r["x"]) > 1e-4   # the input moves the cart
    with pytest.raises(ValueError, match="missing 'omega'"):
        impactlab.simulate(m, duration=1)


def test_poincare_at_a_phase(tmp_path, cli):
    out = tmp_path / "sec.csv"
    cli("poincare", "--model", "A1H", "--omega", 18, "--periods", 60, "--transient", 20, "--phi0", 1.5708, "--out", out)
    r = impactlab.poincare("A1H", 18, 60, transient=20, phi0=1.5708)
    assert list(r) == ["n", "x", "v"] and r["n"][0] == 1
    assert_columns_match(r, out)


def test_bifurcation_over_omega_and_xi(tmp_path, cli):
    out = tmp_path / "diag.csv"
    cli("bifurcation", "--model", "A1G", "--sweep", "down", "--omega-min", 9, "--omega-max", 14, "--steps", 25,
        "--transient", 10, "--record", 20, "--out", out)
    r = impactlab.bifurcation("A1G", "down", range=(9, 14), steps=25, transient=10, record=20)
    assert_columns_match(r, out)
    assert r.protocol == "cf-down" and set(r.transitions) >= {"period_doubling", "windows"}

    out = tmp_path / "xi.csv"
    cli("bifurcation", "--model", "A1H", "--over", "xI", "--range", "-0.012:0.006", "--omega", 18, "--steps", 12,
        "--transient", 5, "--record", 10, "--out", out)
    r = impactlab.bifurcation("A1H", over="xI", range=(-0.012, 0.006), omega=18, steps=12, transient=5, record=10)
    assert list(r) == ["xI", "x", "v", "period"]
    assert_columns_match(r, out)


def test_bifurcation_ramp(tmp_path, cli):
    out = tmp_path / "ef.csv"
    cli("bifurcation", "--model", "A1C", "--sweep", "ramp", "--omega-max", 12, "--ramp-time", 200, "--out", out)
    r = impactlab.bifurcation("A1C", "ramp", omega_max=12, ramp_time=200)
    assert_columns_match(r, out)


def test_orbit_and_its_multipliers(tmp_path, cli):
    out = tmp_path / "orbit.csv"
    p = cli("orbit", "--model", "A1C", "--omega", 10, "--period", 1, "--out", out)
    r = impactlab.orbit("A1C", 10)
    assert_columns_match(r, out)
    section = re.search(r"x = (\S+) m, v = (\S+) m/s", p.stdout)
    assert ("%.12g" % r.section[0], "%.12g" % r.section[1]) == section.groups()
    printed = re.search(r"Floquet multipliers: (.*)", p.stdout).group(1)
    mu = r.multipliers
    if abs(mu[0].imag) < 1e-12:
        assert printed.split(", ")[0] == "%.8g" % mu[0].real
    assert r.stable == ("stable: yes" in p.stdout)
    assert abs(mu[0]) >= abs(mu[1])


def test_continue_branches_and_points(tmp_path, cli):
    cli("continue", "--model", "A1C", "--omega-min", 8, "--omega-max", 13, "--max-period", 2, "--out", tmp_path / "c")
    r = impactlab.continue_("A1C", range=(8, 13), max_period=2)
    assert list(r)[:6] == ["branch", "omega", "x", "v", "period", "stable"]
    assert_columns_match(r, tmp_path / "c" / "branches.csv")
    assert_columns_match(r.points, tmp_path / "c" / "points.csv", fmt=lambda v: "%.12g" % v)
    assert "period_doubling" in list(r.points["kind"])
    doubling = r.points["omega"][list(r.points["kind"]).index("period_doubling")]
    assert doubling == pytest.approx(10.8613339, abs=1e-5)


def test_lyapunov_one_omega_and_sweep(tmp_path, cli):
    p = cli("lyapunov", "--model", "A1C", "--omega", 16, "--periods", 80, "--transient", 20)
    r = impactlab.lyapunov("A1C", 16, periods=80, transient=20)
    assert "lambda_max = %.6g 1/s" % r["lambda_max"] in p.stdout
    assert "lambda_min = %.6g 1/s" % r["lambda_min"] in p.stdout
    out = tmp_path / "ly.csv"
    cli("lyapunov", "--model", "A1C", "--sweep", "up", "--omega-min", 10, "--omega-max", 14, "--steps", 6,
        "--transient", 10, "--record", 20, "--out", out)
    s = impactlab.lyapunov("A1C", sweep="up", range=(10, 14), steps=6, transient=10, record=20)
    assert_columns_match(s, out)


def test_basins_any_thread_count(tmp_path, cli):
    out = tmp_path / "b.csv"
    cli("basins", "--model", "A1G", "--omega", 13, "--grid", 12, "--threads", 2, "--out", out)
    r1 = impactlab.basins("A1G", 13, grid=12, threads=1)
    r2 = impactlab.basins("A1G", 13, grid=12, threads=2)
    assert_columns_match(r1, out)
    assert np.array_equal(r1["label"], r2["label"])
    assert r1.shape == (12, 12) and len(r1.attractors) >= 2


def test_scan_bit_for_bit_any_thread_count(tmp_path, cli):
    out = tmp_path / "plane.csv"
    cli("scan", "--model", "A1C", "--x", "omega:9:13:6", "--y", "xI:-0.004:0.004:3", "--measure", "period,impacts,xrange",
        "--transient", 10, "--record", 20, "--threads", 2, "--out", out)
    r1 = impactlab.scan("A1C", "omega:9:13:6", ("xI", -0.004, 0.004, 3), measures="period,impacts,xrange",
                        transient=10, record=20, threads=1)
    r2 = impactlab.scan("A1C", "omega:9:13:6", "xI:-0.004:0.004:3", measures="period,impacts,xrange",
                        transient=10, record=20, threads=2)
    header, rows = read_csv(out)
    assert list(r1) == header
    for c, name in enumerate(header):   # the CLI prints these to round-trip: the same doubles
        assert [float(row[c]) for row in rows] == list(r1[name]), name
        assert np.array_equal(r1[name], r2[name])


def test_fit_report_and_model(tmp_path, cli, shared):
    record = shared / "data" / "synthetic" / "s1_quadratic_damping.csv.gz"
    cli("fit", record, "--model", "A1H", "--report", tmp_path / "cli", "--no-plots")
    r = impactlab.fit(str(record), impactlab.Model.from_name("A1H"), report=tmp_path / "py", plots=False)
    with open(tmp_path / "cli" / "report.json") as f:
        want = json.load(f)
    assert isinstance(r["model_after"], impactlab.Model)
    found = [e["id"] for e in want["effects_found"]]
    assert found == [e["id"] for e in r["effects_found"]] and "quadratic_damping" in found
    assert [e["id"] for e in r["model_after"].effects] == [e["id"] for e in impactlab.Model.from_json(
        str(tmp_path / "cli" / "model_after.json")).effects]
    assert r["model_after"] == impactlab.Model.from_json(str(tmp_path / "py" / "model_after.json"))
    for key in ("error_before", "error_after"):
        assert r[key] == want[key], key
