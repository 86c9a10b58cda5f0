"""The tests run numpy's OpenBLAS with one thread (tests/conftest.py, ``BLAS_THREADS``), unless the person running
them chose a count: a second OpenBLAS thread per xdist worker spins on the planner's small products and made the
suite's performs up to three times as costly on the 2-core machine. The variables must be set before numpy is first
imported, which a conftest that imported numpy itself would silently defeat."""

from __future__ import annotations

import ctypes
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest


def _openblas_threads() -> int:
    """The thread count of the OpenBLAS that numpy loaded, asked through its own C function."""
    assert np.ones((2, 2)) @ np.ones((2, 2)) is not None  # numpy's BLAS loaded
    libs = sorted({line.split()[-1] for line in Path("/proc/self/maps").read_text().splitlines()
                   if "openblas" in line.lower() and ".so" in line})
    for path in libs:
        lib = ctypes.CDLL(path)
        for name in ("scipy_openblas_get_num_threads64_", "scipy_openblas_get_num_threads",
                     "openblas_get_num_threads64_", "openblas_get_num_threads"):
            if hasattr(lib, name):
                return int(getattr(lib, name)())
    pytest.skip("numpy's BLAS here is not an OpenBLAS this test can ask (no /proc/self/maps entry or symbol)")


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="reads the loaded libraries from /proc")
def test_the_tests_and_the_pythons_they_start_run_numpys_blas_on_the_chosen_threads():
    chosen = os.environ["OPENBLAS_NUM_THREADS"]  # "1" unless the person running the tests set it
    assert "OMP_NUM_THREADS" in os.environ and "MKL_NUM_THREADS" in os.environ
    if chosen == "1":
        assert _openblas_threads() == 1
    code = "import os; print(os.environ['OPENBLAS_NUM_THREADS'], os.environ['OMP_NUM_THREADS'])"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == [chosen, os.environ["OMP_NUM_THREADS"]]
