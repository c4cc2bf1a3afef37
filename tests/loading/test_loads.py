"""Loads as values: the names of the inputs are the fields of `Loads`, in their order."""

from dataclasses import fields

import numpy as np
import pytest

import fretting as fr
from fretting.loading.loads import INPUTS, NAMED, LoadBlock, Loads, edge_loads


def test_the_inputs_are_the_fields_of_loads_in_order():
    """`Loads.given` and the messages read `INPUTS` and `NAMED`: a new field must be named there."""
    assert INPUTS == tuple(field.name for field in fields(Loads)) == tuple(NAMED)


def test_given_names_the_inputs_set():
    assert Loads(1.0).given() == {"Q", "sigma"}
    assert Loads(1.0, 2.0, P=3.0).given() == {"Q", "sigma", "P"}
    assert Loads(float("nan"), delta=1e-6).given() == {"Q", "sigma", "delta"}


@pytest.mark.parametrize("varied", [False, True])
def test_edge_loads_of_a_block_are_those_of_its_steps_bit_for_bit(varied):
    """`edge_loads` of a `LoadBlock` (the engine's windows) and of each step's `Loads` (step by step) agree
    bit for bit; ``Q -+ pi a sigma / 4`` at ``x = -+a`` and ``P`` (the contact's where None)."""
    contact = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e5)
    rng = np.random.default_rng(5)
    Q, sigma = rng.normal(size=40) * 3e4, rng.normal(size=40) * 2e7
    block = LoadBlock(Q, sigma, rng.uniform(5e4, 1.5e5, 40) if varied else None)
    rows = edge_loads(block, contact)
    assert rows.shape == (40, 3)
    assert all(np.array_equal(rows[k], edge_loads(block[k], contact)) for k in range(40))
    np.testing.assert_allclose(rows[:, 1] - rows[:, 0], np.pi * contact.a * sigma / 2, rtol=1e-9, atol=1e-9)
    assert np.array_equal(rows[:, 2], block.P if varied else np.full(40, contact.P))
