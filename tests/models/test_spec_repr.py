"""A model spec prints on one line: its parameters as its constructor takes them, the defaults left
out, and the node angles of a resolved spec by their count, not hundreds of numbers."""

import numpy as np
import pytest

import fretting as fr
from fretting.models import Exact, Grid, InPhase, Mesh, Varying


@pytest.mark.parametrize(
    ("spec", "printed"),
    [
        (Grid(32), "Grid(nodes=32)"),
        (Grid(), "Grid()"),
        (Mesh(), "Mesh(rtol=0.0001)"),
        (Mesh(rtol=1e-3), "Mesh(rtol=0.001)"),
        (Exact(), "Exact()"),
        (InPhase(nodes=96), "InPhase(nodes=96)"),
        (Varying(cells=16), "Varying(cells=16)"),
    ],
)
def test_a_spec_prints_as_its_constructor_reads_and_evaluates_back(spec, printed):
    assert repr(spec) == printed
    assert repr(eval(printed)) == printed  # the names are those imported here


def test_the_node_angles_of_a_resolved_spec_are_counted_not_printed():
    theta = np.linspace(0.0, np.pi, 481)
    printed = repr(Mesh(theta=theta, fallback="capped"))
    assert printed == "Mesh(theta=<481 values>, fallback='capped')"
    assert len(repr(Exact(theta=theta[::2]))) < 40 and "<241 values>" in repr(Exact(theta=theta[::2]))


def test_unresolved_and_resolved_varying_specs_compare_and_hash():
    """An unresolved Varying (no half-width yet) equals another like it and hashes; a resolved one
    differs from it (it was a TypeError: float(None) in its attributes)."""
    contact = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e5)
    unresolved = fr.models.Varying()
    assert unresolved == fr.models.Varying() and hash(unresolved) == hash(fr.models.Varying())
    resolved = unresolved.resolved_for(contact, None)
    assert resolved != unresolved and resolved == unresolved.resolved_for(contact, None)
