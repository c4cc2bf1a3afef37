"""Displacement control: the increments a step solves to find ``Q``, their CPU time, how closely it meets ``delta``.

A step under a prescribed ``delta`` finds the ``Q`` that meets it by trial increments from the same state
(`fretting.engine.follow.displaced`, docs/theory/displacement.md#solve); the step's own increment is the last of
them. For each history the script prints the increments solved per step (the trials: one `Loads` built by
`displaced` each), the CPU time of the run (the median of `--repeats` runs) and the largest distance of the
result's ``delta`` from the prescribed one over the steps, over the largest ``|delta|``: what the time buys.

Histories: the sliding cycle of tests/engine/test_displacement_varying_load.py (a varying ``P``, in and out of
gross slip) on its default (`Jaeger`) and on `Varying()`; two cycles of a 90-degree out-of-phase ellipse of ``Q``
(0.5 f P) and ``sigma`` (0.3 f p0), its ``delta`` prescribed (default: `Varying()`); the shipped example
hertz_fretting_wear_gross_slip (the exact model of ``Q`` alone).

    python benchmarks/displacement_speed.py [--repeats 3]
"""

import argparse
import statistics
import time

import numpy as np

import fretting as fr
from fretting.engine import follow
from fretting.loading.examples import example_path
from fretting.models.exact import transition_displacement

#: The contact of tests/engine/test_displacement_varying_load.py, its datum 5 mm from the middle.
CONTACT = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=5e-3)


def prescribed(history, delta):
    """`history` with the displacements `delta` [m] prescribed at its steps instead of its Q (tests import it)."""
    return fr.History(
        np.full(len(history), np.nan), history.sigma, history.vertex_step, history.cycle, history.P, delta
    )


def sliding_cycle(contact, steps=48):
    """``delta = 2 delta_t sin(t)`` under ``P = P0 (1 + 0.3 sin(1.5 t))``, ``delta_t`` the transition
    displacement at ``P0`` (eq D6): it slides both ways, under a rising and a falling P, and sticks again (the
    history of tests/engine/test_displacement_varying_load.py)."""
    t = np.linspace(0.0, 2 * np.pi, steps + 1)
    P = contact.P * (1 + 0.3 * np.sin(1.5 * t))
    delta = 2 * transition_displacement(contact) * np.sin(t)
    return fr.History(np.full(t.size, np.nan), np.zeros(t.size), [0, steps], None, P, delta)


def scenes():
    """(label, contact, history, options of `fr.simulate`)."""
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    ellipse = fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, 90.0, cycles=2, steps_per_cycle=32)
    wear, history = fr.read_history(example_path("hertz_fretting_wear_gross_slip"))[:2]
    return [
        ("sliding cycle, default", CONTACT, sliding_cycle(CONTACT), {}),
        ("sliding cycle, Varying()", CONTACT, sliding_cycle(CONTACT), {"model": fr.models.Varying()}),
        (
            "out-of-phase ellipse under delta",
            CONTACT,
            prescribed(ellipse, fr.simulate(CONTACT, ellipse).delta.values),
            {},
        ),
        ("hertz_fretting_wear_gross_slip", wear, history, {}),
    ]


class _Counted(follow.Loads):
    """The `Loads` of `follow`, counting those built (`displaced` builds one per trial increment)."""

    built = 0

    def __init__(self, *loads):
        _Counted.built += 1
        super().__init__(*loads)


def measured(contact, history, options, repeats):
    """(result, increments per step, median CPU time [s]) of `repeats` runs."""
    times = []
    for _ in range(repeats):
        _Counted.built = 0
        start = time.process_time()
        result = fr.simulate(contact, history, **options)
        times.append(time.process_time() - start)
    return result, _Counted.built / (len(history) - 1), statistics.median(times)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    follow.Loads = _Counted
    print(f"{'history':<36}{'model':<10}{'steps':>6}{'increments/step':>17}{'CPU [s]':>9}{'delta missed':>14}")
    for label, contact, history, options in scenes():
        result, per_step, seconds = measured(contact, history, options, args.repeats)
        missed = np.max(np.abs(result.delta.values - history.delta)) / np.max(np.abs(history.delta))
        model = result.attrs["model"]
        print(f"{label:<36}{model:<10}{len(history) - 1:>6}{per_step:>17.2f}{seconds:>9.2f}{missed:>14.1e}")


if __name__ == "__main__":
    main()
