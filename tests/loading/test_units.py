"""Units at the boundary of the loading layer: the History constructors take pint quantities, history
files take values with units and a ``[units]`` table, all converted to the SI floats of a history
written in SI; a wrong or unknown unit is a one-line error naming the key; pint stays optional."""

import sys

import numpy as np
import pint
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.errors import HistoryError
from fretting.loading.history import PiecewiseLinear
from fretting.loading.history_file import HistoryFileError, read_history

UNITS = pint.UnitRegistry()
kN_m, N_mm, MPa, mm, um, deg = (UNITS(unit) for unit in ("kN/m", "N/mm", "MPa", "mm", "um", "deg"))


def _same(history, expected):
    assert len(history) == len(expected)
    for name in ("Q", "sigma", "cycle", "P", "delta", "vertex_step"):
        np.testing.assert_array_equal(getattr(history, name), getattr(expected, name), err_msg=name)


def test_sinusoidal_takes_quantities():
    P = {"P_amplitude": 10 * N_mm, "P_mean": 100 * N_mm, "P_phase_deg": np.pi / 2 * UNITS.rad}
    start = (1 * kN_m, 0 * MPa, 100 * N_mm)
    given = fr.History.sinusoidal(30 * kN_m, 20 * MPa, 90 * deg, 2, 16, 5 * kN_m, 10 * MPa, start=start, **P)
    expected = fr.History.sinusoidal(
        30e3, 20e6, 90, 2, 16, 5e3, 10e6, start=(1e3, 0.0, 1e5), P_amplitude=1e4, P_mean=1e5, P_phase_deg=90
    )
    _same(given, expected)


def test_piecewise_linear_takes_array_quantities_and_lists_of_them():
    given = fr.History.piecewise_linear(
        [0, 20, -20] * N_mm, [0 * MPa, 10 * MPa, 5e6 * UNITS.Pa], 4, [100, 110, 100] * N_mm
    )
    _same(given, fr.History.piecewise_linear([0, 20e3, -20e3], [0, 10e6, 5e6], 4, [1e5, 1.1e5, 1e5]))
    moved = fr.History.piecewise_linear(delta=[0, 2] * um, sigma=[0, 1] * MPa, steps_per_segment=2)
    _same(moved, fr.History.piecewise_linear(delta=[0, 2e-6], sigma=[0, 1e6], steps_per_segment=2))


def test_random_amplitude_and_the_explicit_constructors_take_quantities():
    given = fr.History.random_amplitude(
        3, 30 * kN_m, 20 * MPa, 1 * kN_m, 2 * MPa, P_amplitude=5 * N_mm, P_mean=100 * N_mm
    )
    _same(given, fr.History.random_amplitude(3, 30e3, 20e6, 1e3, 2e6, P_amplitude=5e3, P_mean=1e5))
    Q, sigma = [0.0, 1.0, np.nan] * kN_m, [0, 1, 2] * MPa
    explicit = fr.History(Q, sigma, [0, 2], delta=[np.nan, np.nan, 3] * um)
    _same(explicit, fr.History([0.0, 1e3, np.nan], [0, 1e6, 2e6], [0, 2], delta=[np.nan, np.nan, 3e-6]))
    held = PiecewiseLinear([0, 1] * kN_m, [0, 1] * MPa, [4], None, [1, 1] * kN_m)
    _same(held, PiecewiseLinear([0, 1e3], [0, 1e6], [4], None, [1e3, 1e3]))


@pytest.mark.parametrize(
    ("build", "expected"),
    [
        (
            lambda: fr.History.sinusoidal(30 * MPa),
            "Q_amplitude must be a number in N/m (SI) or a quantity in units of N/m",
        ),
        (lambda: fr.History.sinusoidal(1e3, 30 * kN_m), "sigma_amplitude must be a number in Pa (SI)"),
        (lambda: fr.History.sinusoidal(1e3, phase_deg=1 * mm), "phase_deg must be a number in deg (SI)"),
        (lambda: fr.History.piecewise_linear([0, 1] * mm), "Q must be a number in N/m (SI)"),
        (lambda: fr.History.piecewise_linear(delta=[0, 1] * kN_m), "delta must be a number in m (SI)"),
        (lambda: fr.History.sinusoidal(1e3, start=(0 * kN_m, 0 * kN_m)), "start[1] must be a number in Pa (SI)"),
    ],
)
def test_a_quantity_of_another_dimension_is_refused_in_one_line(build, expected):
    with pytest.raises(HistoryError) as caught:
        build()
    assert str(caught.value).startswith(expected) and "\n" not in str(caught.value)


#: The Hertzian contact of conftest in mm, MPa and N/mm, with values of other units written out.
IN_MM = """
[units]
length = "mm"
stress = "MPa"
line_load = "N/mm"

[contact]
profile = "hertz"
R = 50
E = "210 GPa"
nu = 0.3
f = 0.7
P = 100

[[loading]]
kind = "linear"
Q = [20, "-20 kN/m", -20]
sigma = ["10e6 Pa", 5, 5]
steps_per_segment = 4

[[loading]]
kind = "sine"
Q_amplitude = "30 kN/m"
sigma_amplitude = 20
phase_deg = "0.25 turn"
Q_mean = -20
sigma_mean = 5
cycles = 2
steps_per_cycle = 8
"""

IN_SI = (
    HERTZ_TOML
    + """
[[loading]]
kind = "linear"
Q = [20e3, -20e3, -20e3]
sigma = [10e6, 5e6, 5e6]
steps_per_segment = 4

[[loading]]
kind = "sine"
Q_amplitude = 30e3
sigma_amplitude = 20e6
phase_deg = 90
Q_mean = -20e3
sigma_mean = 5e6
cycles = 2
steps_per_cycle = 8
"""
)


def _read(tmp_path, text, name="history.toml"):
    path = tmp_path / name
    path.write_text(text)
    return read_history(path)


def test_a_file_in_mm_mpa_and_n_per_mm_reads_as_the_file_in_si(tmp_path):
    (contact, history), (expected_contact, expected) = _read(tmp_path, IN_MM), _read(tmp_path, IN_SI, "si.toml")
    assert repr(contact) == repr(expected_contact) and contact.profile.R == 0.05 and contact.P == 1e5
    _same(history, expected)


def test_the_units_of_length_hold_for_a_displacement_amplitude_and_mean(tmp_path):
    """``delta_amplitude`` and ``delta_mean`` of a sine block are lengths: in um where the file says so."""
    sine = '[[loading]]\nkind = "sine"\ndelta_amplitude = {}\ndelta_mean = {}\ncycles = 1\nsteps_per_cycle = 8\n'
    in_um = '[units]\nlength = "um"\n' + HERTZ_TOML.replace("R = 0.05", "R = 5e4") + "datum = 5e3\n" + sine.format(2, 1)
    _, history = _read(tmp_path, in_um)
    _, expected = _read(tmp_path, HERTZ_TOML + "datum = 5e-3\n" + sine.format(2e-6, 1e-6), "si.toml")
    np.testing.assert_allclose(history.delta, expected.delta, rtol=1e-15, atol=1e-21)


def test_the_units_table_holds_for_the_tables_a_file_names(tmp_path):
    (tmp_path / "loads.csv").write_text("Q,sigma\n20,10\n-20,5\n")
    csv = '[[loading]]\nkind = "csv"\nfile = "loads.csv"\n'
    _, history = _read(tmp_path, IN_MM.split("[[loading]]")[0] + csv)
    (tmp_path / "si.csv").write_text("Q,sigma\n20e3,10e6\n-20e3,5e6\n")
    _, expected = _read(tmp_path, HERTZ_TOML + csv.replace("loads.csv", "si.csv"), "si.toml")
    _same(history, expected)


@pytest.mark.parametrize(
    ("line", "replaced", "expected"),
    [
        (
            'Q_amplitude = "30 kN/m"',
            'Q_amplitude = "30 MPa"',
            'loading[2].Q_amplitude: found "30 MPa", expected a number [N/mm], or a line load with units, '
            'e.g. "30 kN/m"; MPa does not convert to N/m',
        ),  # noqa: E501
        ('Q_amplitude = "30 kN/m"', 'Q_amplitude = "30 kN/mmm"', "(pint knows no such unit)"),
        ('Q_amplitude = "30 kN/m"', 'Q_amplitude = "kN/m"', 'found "kN/m", expected a number [N/mm], or a line load'),
        (
            'phase_deg = "0.25 turn"',
            'phase_deg = "3 mm"',
            'loading[2].phase_deg: found "3 mm", expected a number [deg], or an angle',
        ),  # noqa: E501
        ('E = "210 GPa"', 'E = "210e9"', 'contact.E: found "210e9", expected a number [MPa], or a stress with units'),
        (
            'length = "mm"',
            'length = "MPa"',
            'units.length: found "MPa", expected a unit of length in quotes, e.g. "mm"; MPa does not convert to m',
        ),  # noqa: E501
        ('length = "mm"', 'length = "1 mm"', 'units.length: found "1 mm", expected a unit of length in quotes'),
        (
            'length = "mm"',
            'force = "N"',
            "units.force: unknown key, expected one of: length, stress, line_load, compliance",
        ),  # noqa: E501
    ],
)
def test_an_unknown_or_inconsistent_unit_is_a_one_line_error(tmp_path, line, replaced, expected):
    assert line in IN_MM
    with pytest.raises(HistoryFileError) as caught:
        _read(tmp_path, IN_MM.replace(line, replaced))
    message = str(caught.value)
    assert expected in message and "\n" not in message
    assert message.startswith(f"{tmp_path / 'history.toml'}:{caught.value.line}: ") and caught.value.line


def test_without_pint_a_file_in_si_reads_and_one_with_units_says_to_install_it(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "pint", None)  # import pint raises ImportError
    _, history = _read(tmp_path, IN_SI)
    assert history.cycle_count == 2
    with pytest.raises(
        HistoryFileError, match=r"units\.length: .* \(a value with units needs pint: pip install pint\)$"
    ):
        _read(tmp_path, IN_MM)
    with pytest.raises(HistoryFileError, match=r"contact\.R: found \"50 mm\", .* needs pint: pip install pint\)$"):
        _read(tmp_path, IN_SI.replace("R = 0.05", 'R = "50 mm"'))
