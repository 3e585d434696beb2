"""Fixtures of the Python module's tests: the CLI they compare against, and a reader of its CSVs."""
import csv
import os
import pathlib
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `impactlab ARGS...` (IMPACTLAB_CLI: the build's program) and returns the finished process."""
    exe = os.environ.get("IMPACTLAB_CLI")
    if not exe or not os.path.exists(exe):
        pytest.fail("IMPACTLAB_CLI must name the impactlab program (ctest sets it)")

    def run(*args, check=True):
        p = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"impactlab {' '.join(map(str, args))} failed ({p.returncode}): {p.stderr}")
        return p

    return run


@pytest.fixture(scope="session")
def shared():
    path = pathlib.Path(os.environ.get("IMPACTLAB_SHARED", pathlib.Path(__file__).resolve().parents[3] / "shared"))
    if not path.is_dir():   # as the C++ suites: a clone without ../shared skips these tests, saying so
        pytest.skip(f"the shared data directory {path} is not here (IMPACTLAB_SHARED names it); skipped, not passed")
    return path


def read_csv(path):
    """(header, rows as lists of strings) of a CSV the CLI wrote."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def g10(value):
    """A number as the CLI prints it into a CSV (an ostream at precision 10: %.10g)."""
    return "%.10g" % value


def assert_columns_match(result, path, fmt=g10, columns=None):
    """Every column of the CLI's CSV equals the result's column of the same name, printed as the CLI prints it."""
    header, rows = read_csv(path)
    assert rows, f"{path} has no rows"
    for name in columns or header:
        assert name in result, f"the result has no column {name!r} (it has {list(result)})"
        col = header.index(name)
        values = result[name]
        assert len(values) == len(rows), f"{name}: {len(values)} values, the CLI wrote {len(rows)}"
        for i, (value, row) in enumerate(zip(values, rows)):
            text = value if isinstance(value, str) else fmt(value)
            assert text == row[col], f"{name}, row {i}: Python {text}, the CLI {row[col]}"
