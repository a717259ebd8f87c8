"""Fixtures of the Python package's tests (run by `meson test`, suite python).

meson passes EOMC (the eomc under test), EOMC_SOURCE_ROOT (the specs) and
PYTHONPATH (the package in the source tree); the cache is a fresh
directory of this session's, so each spec is built once per run.
"""

import os
import subprocess
import tempfile

import numpy as np
import pytest

SOURCE = os.environ.get("EOMC_SOURCE_ROOT",
                        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def spec(name):
    return os.path.join(SOURCE, "specs", name)


@pytest.fixture(scope="session", autouse=True)
def cache_dir():
    with tempfile.TemporaryDirectory(prefix="eomc-pytest-") as d:
        old = os.environ.get("EOMC_CACHE_DIR")
        os.environ["EOMC_CACHE_DIR"] = d
        yield d
        if old is None:
            del os.environ["EOMC_CACHE_DIR"]
        else:
            os.environ["EOMC_CACHE_DIR"] = old


def cli_csv(spec_path, *options):
    """`eomc run SPEC OPTIONS -o FILE`: (exit status, columns, rows as lists of
    float read by Python's float, stderr)."""
    import eomc._build
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "rows.csv")
        p = subprocess.run([eomc._build.compiler(), "run", spec_path, *options, "-o", out],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        with open(out) as f:
            lines = f.read().splitlines()
    columns = lines[0].split(",")
    rows = [[float(c) for c in line.split(",")] for line in lines[1:]]
    return p.returncode, columns, np.array(rows).reshape(len(rows), len(columns)), p.stderr


def same_bits(a, b):
    """Equal to the last bit (NaNs included), as float64."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    b = np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))
