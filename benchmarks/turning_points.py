"""Meshes adapted at the turning points of a history against meshes adapted at every step.

`fretting.adapted_mesh` asks `element_targets` about the increments between turning points of
the load path only (curved stretches cut where they have turned by `fretting.models.galerkin.adaptation.MAX_TURN`).
This script measures what that costs in accuracy: for each scene it adapts a second mesh to
every increment of the history (the stick and slip zones of every step resolved), and compares
nodes, time and the energy of the last cycle with the closed form (Hertz under Q alone,
Mindlin-Deresiewicz) or with that every-step run.

Run:  python benchmarks/turning_points.py   (about 4 minutes on one core)
"""

import time

import harness
import numpy as np

import fretting as fr
from fretting.models import galerkin
from fretting.physics import closed_forms as cf


def every_step_mesh(contact, history, rtol):
    """Mesh refined until no increment of `history` asks for a smaller element."""
    theta = galerkin.initial_theta()
    while True:
        result = fr.simulate(contact, history, mesh=theta)
        ds = np.diff(result.slip.values, axis=0)  # exactly 0 where a node stuck
        scene = galerkin.Mesh(theta=theta).build(contact)
        refined = galerkin.refine(theta, galerkin.element_targets(theta, ds, rtol, scene.breakpoints))
        if refined is theta:
            return theta, result
        theta = refined


def last_cycle(result):
    return float(result.cycle_dissipation[-1])


def main():
    hertz = harness.hertz_contact()
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    scenes = {
        f"Q = +-{psi} fP": (fr.History.sinusoidal(psi * fP, cycles=3), psi * fP) for psi in (0.001, 0.05, 0.5, 0.95)
    }
    scenes |= {
        "in-phase Q, sigma": (fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, cycles=3, steps_per_cycle=128), None),
        "90-degree Q, sigma": (fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, 90, cycles=3, steps_per_cycle=128), None),
    }
    print(
        f"{'scene':22} {'turning points: nodes':>22} {'s':>6} {'error':>9}   "
        f"{'every step: nodes':>18} {'s':>6} {'error':>9}"
    )
    for name, (history, Q_star) in scenes.items():
        began = time.perf_counter()
        turning = fr.simulate(hertz, history)
        turning_s = time.perf_counter() - began
        began = time.perf_counter()
        theta, every = every_step_mesh(hertz, history, fr.DEFAULT_RTOL)
        every_s = time.perf_counter() - began
        reference = cf.mindlin_deresiewicz_energy(hertz, Q_star) if Q_star else last_cycle(every)
        errors = [abs(last_cycle(r) / reference - 1) for r in (turning, every)]
        every_error = f"{errors[1]:9.1e}" if Q_star else f"{'(ref)':>9}"
        print(
            f"{name:22} {turning.sizes['x']:22d} {turning_s:6.2f} {errors[0]:9.1e}   "
            f"{theta.size:18d} {every_s:6.1f} {every_error}"
        )


if __name__ == "__main__":
    main()
