"""The default under Q alone against method 4 on a random history: time and energy.

Seeded random vertices of Q in [-0.9, 0.9] f P, 8 steps per segment, from the contact just
formed, on Hertz and on the rounded flat of tests/test_hard_cases.py. Every step is a new load
change, so the exact model (fretting.models.exact, the default here) builds a new corrective contact
at every step, and no cycle repeats for method 4 to copy. Method 4 runs on the Galerkin mesh
adapted to the default rtol (adaptation included; asked for with rtol=). The total energy of
the two is compared.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/exact_random_history.py [VERTICES]   (200: a few minutes)
"""

import sys
import time

import numpy as np

import fretting as fr

CONTACTS = {
    "Hertz": fr.Contact(fr.Hertz(R=0.05), 115.4e9, 0.6, 1e5),
    "rounded flat": fr.Contact(fr.RoundedFlat(b=1e-3, R=0.02), 115e9, 0.5, 3e5),
}


def timed(contact, history, **model):
    began = time.perf_counter()
    result = fr.simulate(contact, history, **model)
    return result, time.perf_counter() - began


def main(vertices=200):
    psi = np.concatenate([[0.0], np.random.default_rng(1).uniform(-0.9, 0.9, vertices)])
    for name, contact in CONTACTS.items():
        history = fr.History.piecewise_linear(psi * contact.f * contact.P, None, 8)
        exact, exact_s = timed(contact, history)
        mesh, mesh_s = timed(contact, history, rtol=fr.DEFAULT_RTOL)
        steps = len(history) - 1
        difference = abs(mesh.total_dissipation.values / exact.total_dissipation.values - 1)
        print(
            f"{name}, {steps} steps: exact {exact_s:.2f} s ({1e3 * exact_s / steps:.2f} ms per step), "
            f"rtol 1e-4 {mesh_s:.1f} s on {mesh.attrs['nodes']} nodes; total energy differs by {difference:.1e}"
        )


if __name__ == "__main__":
    main(*(int(argument) for argument in sys.argv[1:]))
