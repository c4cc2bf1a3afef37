"""Gross slip of method 4's models under displacement control, with and without a bulk tension.

On the scene of tests/models/test_sliding_sigma.py (Hertz, ``f = 0.6``, ``P = 1e5 N/m``, datum 5 mm),
prints for the grid, uniform Galerkin meshes and the cells of `fretting.models.Varying`:

- the largest ``|E / (f P |d delta|) - 1|`` over the steps that slide on (eq D12), ``sigma`` moving
  from ``0.3`` to ``0.5 f p0`` while the contact slides;
- the largest error of the slip of the last such step against ``d delta + d sigma x / (2 E_star)``
  (eq D11), in units of ``d sigma a / (2 E_star)``;
- against the exact model of ``Q`` alone on a cycle of +-1.5 delta_t at ``sigma = 0``: the largest
  error of ``Q`` over the steps [f P], of the cycle's energy [relative], and whether the regime of
  every step is the same.

    python benchmarks/gross_slip_sigma.py
"""

import numpy as np

import fretting as fr
from fretting.models.galerkin import uniform_theta
from fretting.results.variables import REGIMES
from fretting.studies.running import sliding_cycles, transition_displacement

CONTACT = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=5e-3, compliance=2e-12)
GROSS = REGIMES.index("gross_slip")


def tension_then_sliding(contact, steps=4):
    """``sigma`` to ``0.3 f p0`` at ``delta = 0``, ``delta`` past the transition, then both on together."""
    delta_t, fp0 = transition_displacement(contact), contact.f * contact.p0
    delta = [0.0, 0.0, 1.5 * delta_t, 1.8 * delta_t]
    sigma = [0.0, 0.3 * fp0, 0.3 * fp0, 0.5 * fp0]
    return fr.History.piecewise_linear(delta=delta, sigma=sigma, steps_per_segment=steps)


def slides(contact, spec):
    """(largest relative error of a slide's energy, error of the strain mismatch law) of `spec`."""
    fP = contact.f * contact.P
    result = fr.simulate(contact, tension_then_sliding(contact), spec)
    regime = result.regime.values
    on = np.flatnonzero((regime[1:] == GROSS) & (regime[:-1] == GROSS)) + 1
    d_delta = np.diff(result.delta.values)
    energy = np.max(np.abs(result.dissipation.values[on] / (fP * np.abs(d_delta[on - 1])) - 1))
    x = result.x.values - contact.centre
    ds = result.slip.values[-1] - result.slip.values[-2]
    d_sigma = float(np.diff(result.sigma.values)[-1])
    law = np.max(np.abs(ds - (d_delta[-1] + d_sigma * x / (2 * contact.E_star))))
    return energy, law / (d_sigma * contact.a / (2 * contact.E_star))


def against_exact(contact, spec, exact):
    """(error of Q [f P], of the cycle's energy [relative], same regimes) of `spec` on the cycle of `exact`."""
    history = sliding_cycles(1.5 * transition_displacement(contact), 1, 16)
    result = fr.simulate(contact, history, spec)
    fP = contact.f * contact.P
    return (
        np.max(np.abs(result.Q.values - exact.Q.values)) / fP,
        abs(float(result.cycle_dissipation[0] / exact.cycle_dissipation[0]) - 1),
        bool(np.array_equal(result.regime.values, exact.regime.values)),
    )


def main():
    exact = fr.simulate(CONTACT, sliding_cycles(1.5 * transition_displacement(CONTACT), 1, 16), fr.models.Exact())
    specs = [("grid 128", fr.models.Grid(128))]
    specs += [(f"mesh of {n} elements", fr.models.Mesh(theta=uniform_theta(n))) for n in (32, 64, 128, 256)]
    specs += [(f"{n} cells", fr.models.Varying(n)) for n in (64, 128, 256)]
    print("model | slide energy error | strain mismatch error | Q error [f P] | cycle energy error | regimes equal")
    for label, spec in specs:
        energy, law = slides(CONTACT, spec)
        Q, cycle, same = against_exact(CONTACT, spec, exact)
        print(f"{label} | {energy:.1e} | {law:.1e} | {Q:.1e} | {cycle:.1e} | {same}")


if __name__ == "__main__":
    main()
