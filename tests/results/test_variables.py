"""The dataset contract: the entries of `VARIABLES` that follow from the per-cycle fields hold their facts."""

import pytest

from fretting.results.variables import ACCUMULATED, CYCLE_FIELDS, CYCLE_PEAKS, VARIABLES, variable


def test_every_entry_has_dims_units_and_a_long_name():
    for name, (dims, units, long_name) in VARIABLES.items():
        assert isinstance(dims, tuple) and all(isinstance(dim, str) for dim in dims), name
        assert isinstance(units, str) and units, name
        assert isinstance(long_name, str) and long_name, name


@pytest.mark.parametrize("name", CYCLE_FIELDS)
def test_a_per_cycle_field_is_on_cycles_and_nodes(name):
    assert VARIABLES[name][0] == ("cycle_number", "x")


@pytest.mark.parametrize("name", CYCLE_PEAKS)
def test_a_peak_is_a_per_cycle_field_with_a_state_in_its_units(name):
    assert name in CYCLE_FIELDS
    dims, units, _ = VARIABLES[f"state_{name}"]
    assert dims == ("x",) and units == VARIABLES[name][1]


@pytest.mark.parametrize("name", ACCUMULATED)
def test_an_accumulated_field_is_on_nodes_in_the_units_of_its_source(name):
    source = ACCUMULATED[name]
    assert source in CYCLE_FIELDS
    dims, units, long_name = VARIABLES[name]
    assert dims == ("x",) and units == VARIABLES[source][1]
    assert long_name.startswith("largest ") or name == "w_total"


def test_every_per_cycle_field_but_the_energy_density_has_a_maximum():
    assert ACCUMULATED == {"w_total": "w"} | {f"{name}_max": name for name in CYCLE_FIELDS if name != "w"}
    assert VARIABLES["state_w"][1] == VARIABLES["w_total"][1] == VARIABLES["w"][1]


def test_variable_carries_units_and_long_name():
    built = variable("w_total", [1.0, 2.0])
    assert built.dims == ("x",) and built.attrs == {"units": VARIABLES["w"][1], "long_name": VARIABLES["w_total"][2]}
    assert variable("w", [[1.0]], dims=("field_cycle", "x")).dims == ("field_cycle", "x")
