"""States that the contact cannot be in (issue 38): a hand-made slip far beyond anything the loads can
produce ran and returned |q| > f p or energy from nothing. `State.check` refuses them in one line."""

import dataclasses

import numpy as np
import pytest

import fretting as fr
from fretting.engine.recorder import final_state
from fretting.errors import HistoryError

FIRST = fr.History.piecewise_linear([0, 30e3], None, 8)
LATER = fr.History.piecewise_linear([30e3, -30e3, 30e3], None, 8)


@pytest.fixture(params=[fr.models.Grid(32), fr.models.Mesh(rtol=1e-2), fr.models.Exact()], ids=str)
def state(request, hertz):
    """The state after loading to Q = 0.43 f P with the model of the parameter."""
    return final_state(fr.simulate(hertz, FIRST, request.param))


def test_a_state_run_to_is_continued(hertz, state):
    assert float(fr.simulate(hertz, LATER, state=state).total_dissipation) > state.dissipated


@pytest.mark.parametrize("slip", [1e10, 1e-3], ids=["1e10-m", "1-mm"])
def test_a_uniform_slip_the_loads_cannot_produce_is_refused_in_one_line(hertz, state, slip):
    uniform = np.full(state.slip.size, slip)
    made = dataclasses.replace(state, slip=uniform, episode_start=uniform)
    with pytest.raises(HistoryError, match="^state.slip .*: a slip the (loads|recorded .*) cannot produce$") as error:
        fr.simulate(hertz, LATER, state=made)
    assert "\n" not in str(error.value)


@pytest.mark.parametrize("model", [fr.models.Grid(32), fr.models.Mesh(rtol=1e-2)], ids=str)
def test_a_slip_without_the_energy_it_took_is_refused(hertz, model):
    """Method 4's models: int f p |s| dx is at most the energy dissipated since the contact was formed."""
    state = final_state(fr.simulate(hertz, FIRST, model))
    with pytest.raises(HistoryError, match=r"^state.slip needs at least .* J/m dissipated"):
        fr.simulate(hertz, LATER, state=dataclasses.replace(state, dissipated=0.0))


def test_a_traction_beyond_f_p_is_refused(hertz):
    """Twice the slip of a state on the grid: the slip zones' traction passes f p."""
    state = final_state(fr.simulate(hertz, FIRST, fr.models.Grid(32)))
    doubled = dataclasses.replace(state, slip=2 * state.slip, dissipated=10 * state.dissipated)
    with pytest.raises(HistoryError, match=r"^state.slip leaves a traction above f p by .* \(Coulomb\)"):
        fr.simulate(hertz, LATER, state=doubled)
