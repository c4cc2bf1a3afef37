"""Energy of small load cycles on models of fixed nodes against the exact model, and the note naming them (issue 38).

Cycles of ``Q = A f P sin`` (two cycles of 32 steps; the second's energy) on the tests' Hertz contact
(R = 50 mm, steel, f = 0.7, P = 100 N/mm) and on a rounded flat (b = 0.2 mm, R = 50 mm), for amplitudes
``A`` from 1e-6 to 0.5, on Grid(96), Grid(384) (the grid's default), Grid(1536), a given mesh of 200 and
of 800 nodes equally spaced in ``theta`` and the mesh adapted to the energy (default rtol), against the
exact model of ``Q`` alone. Each row: the nodes in the cycle's estimated slip zone
(`fretting.results.notes.edge_slip_nodes`, or the recorded slip's where wider), whether the result's
``model_unresolved`` names the cycle, and ``W / W_exact - 1``. Then the largest error of the cycles not
flagged (to be within the README's 1e-4) and the smallest of those flagged (the criterion is on the safe
side: a cycle of few nodes may happen to err by less).

Run:  python benchmarks/unresolved_cycles.py
"""

import numpy as np

import fretting as fr
from fretting.results.notes import UNRESOLVED, edge_slip_nodes, observed_slip_nodes

AMPLITUDES = (1e-6, 1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 2e-2, 5e-2, 0.1, 0.2, 0.3, 0.4, 0.5)
E_STAR = fr.plane_strain_modulus(210e9, 0.3)
CONTACTS = {
    "hertz": fr.Contact(fr.Hertz(0.05), E_STAR, 0.7, 1e5),
    "rounded flat": fr.Contact(fr.RoundedFlat(2e-4, 0.05), E_STAR, 0.7, 1e5),
}
MODELS = {
    "Grid(96)": fr.models.Grid(96),
    "Grid(384)": fr.models.Grid(),
    "Grid(1536)": fr.models.Grid(1536),
    "Mesh(200 given)": fr.models.Mesh(theta=np.linspace(0, np.pi, 200)),
    "Mesh(800 given)": fr.models.Mesh(theta=np.linspace(0, np.pi, 800)),
    "Mesh() adapted": fr.models.Mesh(),
}
TARGET = 1e-4  # the README's energy promise


def main():
    flagged, unflagged = [], []
    print(f"{'contact':13s} {'A [f P]':>8s} {'model':16s} {'slip nodes':>10s} {'flagged':>7s} {'W/W_exact - 1':>14s}")
    for name, contact in CONTACTS.items():
        for A in AMPLITUDES:
            history = fr.History.sinusoidal(A * contact.f * contact.P, cycles=2, steps_per_cycle=32)
            exact = fr.simulate(contact, history, fr.models.Exact()).cycle_dissipation.values[-1]
            for label, model in MODELS.items():
                result = fr.simulate(contact, history, model)
                error = result.cycle_dissipation.values[-1] / exact - 1
                ranges = result.cycle_load_range.values[-1:]
                estimated = edge_slip_nodes(result.attrs, result.x.values, result.p.values, ranges)[0]
                recorded = observed_slip_nodes(result.stick.values, result.cycle.values, np.array([2]))[0]
                nodes = max(estimated, recorded)
                note = result.attrs.get(UNRESOLVED, "")
                named = "(cycle 2)" in note or "to 2)" in note
                (flagged if named else unflagged).append(abs(error))
                print(f"{name:13s} {A:8.0e} {label:16s} {nodes:10d} {'yes' if named else 'no':>7s} {error:+14.2e}")
    print(f"largest |error| of the cycles not flagged: {max(unflagged):.2e} (target {TARGET:g})")
    print(f"smallest |error| of the cycles flagged: {min(flagged):.2e}")
    print(f"flagged: {len(flagged)} cycles, of which {sum(e > TARGET for e in flagged)} err by more than {TARGET:g}")


if __name__ == "__main__":
    main()
