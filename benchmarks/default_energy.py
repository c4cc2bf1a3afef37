"""Energy per steady cycle of a Hertz contact under Q = +-Q*: the default and method 4.

Sine cycles of 64 steps, three of them; cycles 2 and 3 against the Mindlin-Deresiewicz (Masing)
closed form, `fretting.physics.closed_forms.mindlin_deresiewicz_energy`, with the nodes and the
wall time of each run. The default runs Q alone on this symmetric profile with the exact model
(fretting.models.exact); method 4 runs on the Galerkin mesh adapted to the default rtol (adaptation included).
tests/models/test_masing.py holds the first to 1e-12 (+ 1e-15 / psi), tests/models/test_galerkin.py six of
these amplitudes of the second to 1e-4.

Run:  python benchmarks/default_energy.py   (a few seconds)
"""

import time

import numpy as np

import fretting as fr
from fretting.physics.closed_forms import mindlin_deresiewicz_energy

AMPLITUDES = (1e-6, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95)


def main():
    contact = fr.Contact(fr.Hertz(R=0.05), 115.4e9, 0.6, 1e5)
    for psi in AMPLITUDES:
        Q_star = psi * contact.f * contact.P
        history = fr.History.sinusoidal(Q_star, cycles=3, steps_per_cycle=64)
        for label, model in (("default (exact)", {}), ("rtol 1e-4", {"rtol": fr.DEFAULT_RTOL})):
            began = time.perf_counter()
            result = fr.simulate(contact, history, **model)
            seconds = time.perf_counter() - began
            W = mindlin_deresiewicz_energy(contact, Q_star)
            error = np.max(np.abs(result.cycle_dissipation.values[1:] / W - 1))
            nodes = result.attrs["nodes"]
            print(f"Q*/fP = {psi:<6g} {label:16s} {nodes:4d} nodes {seconds:6.3f} s  energy error {error:.1e}")


if __name__ == "__main__":
    main()
