"""Shared scenes: the SI Hertz contact of the issue, and its unit-free twin."""

import numpy as np
import pytest

import fretting as fr
from fretting.contact import plane_strain_modulus

E_SI, NU_SI = 210e9, 0.3

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


def hertz_si():
    """R = 50 mm, E = 210 GPa, nu = 0.3, P = 100 N/mm, f = 0.6."""
    return fr.Contact(fr.Hertz(0.05), plane_strain_modulus(E_SI, NU_SI), 0.6, 1e5)


@pytest.fixture
def hertz():
    return hertz_si()


@pytest.fixture
def unit_hertz():
    """a = 1, p0 = 1 (R = 1/2, E_star = 1), f = 1."""
    return fr.Contact(fr.Hertz(0.5), 1.0, 1.0, np.pi / 2)


def final(contact, Q, sigma=None, steps=8, **options):
    """Last step of a proportional path from the virgin contact to (Q, sigma)."""
    sigma = None if sigma is None else [0.0, sigma]
    return fr.simulate(contact, fr.History.piecewise_linear([0.0, Q], sigma, steps), **options).isel(step=-1)
