"""Fixtures: the SI Hertz contact of the issue (`harness.hertz_contact`), and its unit-free twin.

The scenes the tests share with the benchmarks are in benchmarks/harness.py, the checks the tests
share in tests/checks.py; pytest finds both through ``pythonpath`` (pyproject.toml).
"""

import os

# One BLAS thread, set before NumPy loads OpenBLAS: on 2 cores its two threads make the dense
# solves of a few hundred nodes up to ten times slower (benchmarks/blas_threads.py).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from harness import hertz_contact  # noqa: E402
from hypothesis import settings  # noqa: E402

import fretting as fr  # noqa: E402

# Under CI the property tests draw one fixed sequence of examples, so that `CI=true pytest`
# reproduces a red CI. Recent Hypothesis does this by itself; the lowest version the project
# supports (pyproject.toml) draws new examples on every run.
if os.environ.get("CI"):
    settings.register_profile("fixed-examples", derandomize=True, database=None)
    settings.load_profile("fixed-examples")

#: The contact table of a history file for a Hertz scene (f = 0.7).
HERTZ_TOML = """\
[contact]
profile = "hertz"
R = 0.05
E = 210e9
nu = 0.3
f = 0.7
P = 1e5
"""

#: Two cycles of Q and sigma in phase on that contact (f P = 70 kN/m): a short cyclic history file.
SINE_TOML = (
    HERTZ_TOML
    + """
[[loading]]
kind = "sine"
Q_amplitude = 30e3
sigma_amplitude = 20e6
cycles = 2
steps_per_cycle = 16
"""
)


@pytest.fixture
def hertz():
    return hertz_contact()


@pytest.fixture
def unit_hertz():
    """a = 1, p0 = 1 (R = 1/2, E_star = 1), f = 1."""
    return fr.Contact(fr.Hertz(0.5), 1.0, 1.0, np.pi / 2)


def final(contact, Q, sigma=None, steps=8, **options):
    """Last step of a proportional path from the virgin contact to (Q, sigma)."""
    sigma = None if sigma is None else [0.0, sigma]
    return fr.simulate(contact, fr.History.piecewise_linear([0.0, Q], sigma, steps), **options).isel(step=-1)
