"""Error against the closed forms, and cost, for several node counts.

Run: python benchmarks/accuracy_vs_nodes.py

Cases (Hertz, R = 50 mm, E = 210 GPa, nu = 0.3, P = 100 N/mm, f = 0.6):
Cattaneo-Mindlin at Q/fP = 0.05, 0.2, 0.5, 0.8, 0.95 (stick ends, traction, slip); Mindlin-
Deresiewicz unloading from 0.8 fP to 0.3, -0.2, -0.7 fP (stick ends, traction); bulk tension
alone at sigma/(f p0) = 0.3, 1, 2.5, 3.5 (stick ends, eq 23). Traction errors exclude 0.02 a
around each stick/slip boundary. Cost: a 10-vertex random Q/sigma history, 8 steps a segment.
"""

import time

import harness
import numpy as np

import fretting as fr
from fretting.analysis.accuracy import BAND, traction_error
from fretting.physics import closed_forms as cf


def final(contact, Q, sigma, nodes):
    """Last step of 8 proportional steps from the virgin contact to ``(Q, sigma)``."""
    return fr.simulate(contact, fr.History.piecewise_linear([0, Q], [0, sigma], 8), nodes=nodes).isel(step=-1)


def errors(contact, nodes):
    fP, fp0, a = contact.f * contact.P, contact.f * contact.p0, contact.a
    worst = {"stick ends /a": 0.0, "traction /fp0": 0.0, "slip /max": 0.0}

    def update(key, value):
        worst[key] = max(worst[key], value)

    for psi in (0.05, 0.2, 0.5, 0.8, 0.95):
        Q = psi * fP
        r = final(contact, Q, 0.0, nodes)
        x, b = r.x.values, cf.stick_half_width(contact, Q)
        update("stick ends /a", abs(r.stick_end.values[0] - b) / a)
        q_exact = cf.cattaneo_mindlin_traction(contact, Q, x)
        update("traction /fp0", traction_error(x, r.q.values, q_exact, [-b, b], BAND * a) / fp0)
        slip = cf.cattaneo_mindlin_slip(contact, Q, x)
        update("slip /max", np.abs(r.slip.values - slip).max() / slip.max())
    Q_star = 0.8 * fP
    for Q_end in (0.3 * fP, -0.2 * fP, -0.7 * fP):
        history = fr.History.piecewise_linear([0, Q_star, Q_end], None, [8, 16])
        r = fr.simulate(contact, history, nodes=nodes).isel(step=-1)
        x = r.x.values
        c = a * np.sqrt(1 - (Q_star - Q_end) / (2 * fP))
        b = cf.stick_half_width(contact, Q_star)
        update("stick ends /a", abs(r.stick_end.values[0] - c) / a)
        q_exact = cf.mindlin_deresiewicz_traction(contact, Q_star, Q_end, x)
        update("traction /fp0", traction_error(x, r.q.values, q_exact, [-c, c, -b, b], BAND * a) / fp0)
    for tau in (0.3, 1.0, 2.5, 3.5):
        sigma = tau * fp0
        r = final(contact, 0.0, sigma, nodes)
        update("stick ends /a", abs(r.stick_end.values[0] - cf.bulk_tension_stick_half_width(contact, sigma)) / a)
    return worst


def cost(contact, nodes, repeats=3):
    history = harness.baseline_history(contact, 8)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fr.simulate(contact, history, nodes=nodes)
        times.append(time.perf_counter() - start)
    return np.median(times) / (len(history) - 1)


def main():
    contact = harness.hertz_contact()
    header = ("nodes", "stick ends /a", "ends /spacing", "traction /fp0", "slip /max", "ms/step")
    print(" ".join(f"{name:>14}" for name in header))
    for nodes in (128, 256, 384, 512, 768):
        worst = errors(contact, nodes)
        spacing = np.pi / nodes  # node spacing at the centre [a]
        row = (worst["stick ends /a"], worst["stick ends /a"] / spacing, worst["traction /fp0"], worst["slip /max"])
        print(f"{nodes:>14} " + " ".join(f"{v:>14.2e}" for v in row) + f" {cost(contact, nodes) * 1e3:>14.2f}")


if __name__ == "__main__":
    main()
