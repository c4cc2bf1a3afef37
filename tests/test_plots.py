"""Figures: every one draws on given axes, labels its axes with units, and `figures_for` picks the right ones."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402 - after choosing the backend

import fretting as fr  # noqa: E402
from fretting import plots  # noqa: E402

NODES = 32


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


@pytest.fixture(scope="module")
def cycled(contact):
    """Q and sigma 90 degrees out of phase, three cycles."""
    history = fr.History.sinusoidal(
        0.6 * contact.f * contact.P, 0.5 * contact.f * contact.p0, phase_deg=90.0, cycles=3, steps_per_cycle=16
    )
    return fr.simulate(contact, history, nodes=NODES)


def axes():
    return Figure(layout="constrained").subplots()


def test_every_figure_draws_on_the_given_axes(cycled):
    names = plots.figures_for(cycled)
    assert names == list(plots.FIGURES)
    for name in names:
        ax = axes()
        assert plots.FIGURES[name](cycled, ax=ax) is ax, name
        assert ax.has_data(), name
        assert ax.get_xlabel() and ax.get_ylabel(), name
        ax.figure.canvas.draw()  # raises on bad mathtext


def test_axis_labels_carry_units_or_normalisation(cycled):
    expected = {
        "traction": ("$x / a$", "$q / (f p_0)$"),
        "surface_stress": ("$x / a$", "$\\sigma_{xx} / (f p_0)$"),
        "loops": ("$\\delta_Q$ [µm]", "$Q / (f P)$"),
        "energy": ("cycle", "dissipation $E_d$ [mJ/m]"),
        "dissipation_density": ("$x / a$", "$w$ [J/m²]"),
        "slip_amplitude": ("$x / a$", "slip amplitude $\\delta$ [µm]"),
    }
    for name, (xlabel, ylabel) in expected.items():
        ax = plots.FIGURES[name](cycled, ax=axes())
        assert (ax.get_xlabel(), ax.get_ylabel()) == (xlabel, ylabel)


def test_loops_draw_each_cycle_from_its_starting_state(cycled):
    ax = plots.loops(cycled, cycles=[2, 3], ax=axes())
    fP = cycled.attrs["f"] * cycled.attrs["P"]
    for line, first in zip(ax.get_lines(), (32, 48), strict=True):  # a 16-step ramp, then 16 steps per cycle
        x, y = line.get_data()
        np.testing.assert_array_equal(x, cycled.delta_Q.values[first : first + 17] * 1e6)
        np.testing.assert_array_equal(y, cycled.Q.values[first : first + 17] / fP)
        assert cycled.cycle.values[first] != cycled.cycle.values[first + 1] == cycled.cycle.values[first + 16]
    with pytest.raises(ValueError, match="not recorded whole"):
        plots.loops(cycled.isel(step=slice(0, 40)), cycles=[2], ax=axes())


def test_results_without_cycles_get_the_snapshots_only(contact):
    monotonic = fr.simulate(contact, fr.History.piecewise_linear([0, 0.5 * contact.f * contact.P]), nodes=NODES)
    assert plots.figures_for(monotonic) == ["traction", "slip", "surface_stress", "hysteresis"]
    with pytest.raises(ValueError, match="no load cycles"):
        plots.cycle_energy(monotonic, ax=axes())


def test_shear_alone_has_no_sigma_loops(contact):
    result = fr.simulate(contact, fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=2), nodes=NODES)
    assert "sigma_loops" not in plots.figures_for(result) and "loops" in plots.figures_for(result)


def test_long_runs_use_logarithmic_axes(contact):
    history = fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=plots.LOG_CYCLES, steps_per_cycle=8)
    result = fr.simulate(contact, history, nodes=NODES)
    for draw in (plots.cycle_energy, plots.peak_density):
        ax = draw(result, ax=axes())
        assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
    ax = plots.dissipation_density(result, ax=axes())
    labels = [line.get_label() for line in ax.get_lines()]
    assert len(labels) == plots.CURVES and labels[0] == "cycle 1" and labels[-1] == f"cycle {plots.LOG_CYCLES}"


def test_partly_recorded_runs(contact):
    """Energy figures need no recorded steps; loops need a cycle recorded whole."""
    history = fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=4, steps_per_cycle=16)
    sparse = fr.simulate(contact, history, nodes=NODES, record=np.arange(0, len(history), 5))
    names = plots.figures_for(sparse)
    assert "loops" not in names and {"energy", "dissipation_density", "peak_density"} <= set(names)
    for name in names:
        plots.FIGURES[name](sparse, ax=axes())
