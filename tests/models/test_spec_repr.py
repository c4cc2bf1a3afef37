"""A model spec prints on one line: its parameters as its constructor takes them, the defaults left
out, and the node angles of a resolved spec by their count, not hundreds of numbers."""

import numpy as np
import pytest

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
