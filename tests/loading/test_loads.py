"""Loads as values: the names of the inputs are the fields of `Loads`, in their order."""

from dataclasses import fields

from fretting.loading.loads import INPUTS, NAMED, Loads


def test_the_inputs_are_the_fields_of_loads_in_order():
    """`Loads.given` and the messages read `INPUTS` and `NAMED`: a new field must be named there."""
    assert INPUTS == tuple(field.name for field in fields(Loads)) == tuple(NAMED)


def test_given_names_the_inputs_set():
    assert Loads(1.0).given() == {"Q", "sigma"}
    assert Loads(1.0, 2.0, P=3.0).given() == {"Q", "sigma", "P"}
    assert Loads(float("nan"), delta=1e-6).given() == {"Q", "sigma", "delta"}
