"""Figures: every one draws on given axes, labels its axes with units, and `figures_for` picks the right ones."""

import re

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402 - after choosing the backend

import fretting as fr  # noqa: E402
from fretting import plots  # noqa: E402
from fretting.analysis import nucleation  # noqa: E402

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
    assert names == [name for name in plots.FIGURES if name != "contact_edges"]  # that one: P varies
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
        "loops": ("slip part of the displacement, $\\delta_Q$ [µm]", "$Q / (f P)$"),
        "energy": ("cycle", "dissipation $E_d$ [mJ/m]"),
        "dissipation_density": ("$x / a$", "$w$ [J/m²]"),
        "slip_amplitude": ("$x / a$", "slip amplitude $\\delta$ [µm]"),
    }
    for name, (xlabel, ylabel) in expected.items():
        ax = plots.FIGURES[name](cycled, ax=axes())
        assert (ax.get_xlabel(), ax.get_ylabel()) == (xlabel, ylabel)


def test_loops_draw_each_cycle_from_its_starting_state(cycled):
    ax = plots.loops(cycled, cycles=[1, 2], ax=axes())
    fP = cycled.attrs["f"] * cycled.attrs["P"]
    for line, first in zip(ax.get_lines(), (16, 32), strict=True):  # a 16-step ramp, then 16 steps per cycle
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
    named = [int(n) for line in ax.get_lines() for n in re.findall(r"\d+", line.get_label())]
    assert len(named) == plots.CURVES and named[0] == 1 and named[-1] == plots.LOG_CYCLES  # some drawn as one


def test_partly_recorded_runs(contact):
    """Energy figures need no recorded steps; loops need a cycle recorded whole."""
    history = fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=4, steps_per_cycle=16)
    sparse = fr.simulate(contact, history, nodes=NODES, record=np.arange(0, len(history), 5))
    names = plots.figures_for(sparse)
    assert "loops" not in names and {"energy", "dissipation_density", "peak_density"} <= set(names)
    for name in names:
        plots.FIGURES[name](sparse, ax=axes())


def test_loop_titles_say_which_part_of_the_energy_the_area_is(cycled, contact):
    """With sigma varying too, the Q loop's area is only the work of Q; under Q alone it is the energy per cycle."""
    assert "part of the energy per cycle that Q does" in plots.loops(cycled, ax=axes()).get_title()
    assert "that sigma does" in plots.sigma_loops(cycled, ax=axes()).get_title()
    alone = fr.simulate(contact, fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=2), nodes=NODES)
    assert plots.loops(alone, ax=axes()).get_title() == "hysteresis loops of Q (area: energy per cycle)"


def test_no_loops_of_Q_when_Q_is_zero(contact):
    result = fr.simulate(contact, fr.History.sinusoidal(0.0, 0.5 * contact.f * contact.p0, cycles=2), nodes=NODES)
    names = plots.figures_for(result)
    assert "loops" not in names and "hysteresis" not in names and "sigma_loops" in names


def test_legends_name_the_step_not_the_row(contact):
    history = fr.History.sinusoidal(0.5 * contact.f * contact.P, 0.3 * contact.f * contact.p0, cycles=2)
    result = fr.simulate(contact, history, nodes=NODES, record=np.arange(0, len(history), 7))
    steps = plots.snapshot_steps(result)
    assert set(steps) <= set(result.step.values) and steps[-1] == result.step.values[-1]
    for draw in (plots.traction, plots.slip, plots.surface_stress):
        labels = [
            line.get_label() for line in draw(result, ax=axes()).get_lines() if line.get_label().startswith("step")
        ]
        assert [int(label.split(":")[0].split()[1]) for label in labels] == list(steps)
    with pytest.raises(ValueError, match=r"steps \[1\] are not recorded"):
        plots.traction(result, steps=[1], ax=axes())


def test_surface_stress_figure_shows_the_specimen_by_default(cycled):
    """Body 2 with the bulk stress sigma, as `nucleation.surface_stress`; the pad when asked."""
    fp0 = cycled.attrs["f"] * cycled.attrs["p0"]
    ax = plots.surface_stress(cycled, steps=[20], ax=axes())
    assert ax.get_title().startswith("surface direct stress, specimen (body 2")
    drawn = ax.get_lines()[0].get_ydata()
    expected = nucleation.surface_stress(cycled, body=2, bulk=0.0).sel(step=20).values / fp0
    np.testing.assert_array_equal(drawn, expected)
    assert "pad (body 1" in plots.surface_stress(cycled, body=1, ax=axes()).get_title()


def test_curves_the_same_to_the_eye_are_drawn_once_and_named_together(contact):
    """Under Q alone the steady cycles repeat: their loops and densities are one curve, whose legend
    names every cycle it stands for; the first cycle, from the unloaded state, is its own."""
    result = fr.simulate(contact, fr.History.sinusoidal(0.5 * contact.f * contact.P, cycles=3), nodes=NODES)
    for draw in (plots.loops, plots.dissipation_density):
        ax = draw(result, ax=axes())
        assert [line.get_label() for line in ax.get_lines()] == ["cycle 1", "cycle 2 (= 3)"]
    distinct = plots._distinct([(np.arange(3.0), np.zeros(3)), (np.arange(3.0), np.full(3, 0.01))], [1, 2])
    assert [numbers for _, numbers in distinct] == [[1], [2]]  # 0.01 apart on a range of 0.01: two curves
