"""Accuracy and cost of the P1 Galerkin scene on adapted meshes, beside the Chebyshev engine.

Run: python benchmarks/galerkin_convergence.py [--rtol 1e-3 1e-4] [--no-chebyshev]

Each case runs the adaptive loop of `harness.adapt` (run the history, reduce
`element_targets` over every increment, `refine`, until the mesh stays) from
`galerkin.initial_theta()`, then reports the error of the settled mesh against the closed
forms, its nodes, the passes it took and the wall time per increment on it (one BLAS thread).

Cases (Hertz, R = 50 mm, E = 210 GPa, nu = 0.3, P = 100 N/mm, f = 0.6):
- cycle psi: energy of the second cycle of Q = +-psi f P, 4 increments a segment, relative to
  the Masing closed form (`fretting.physics.closed_forms.mindlin_deresiewicz_energy`);
- CM psi: Cattaneo-Mindlin after 4 increments: stick ends /a, traction /(f p0) away from
  0.02 a of the ends, slip /max;
- MD Q_end: 0 -> 0.8 f P -> Q_end (4 + 8 increments): stick ends /a, traction /(f p0);
- tension tau: bulk tension sigma = tau f p0 alone (eq 23), stick ends /a;
- rounded flat psi: b = 1 mm, R = 20 mm, Ciavarella-Jaeger stick ends /a;
- flat punch: Q up to 0.999999 f P, largest |slip| (must be exactly 0).
The Chebyshev rows run the same histories on the fixed grid of `fretting.models.collocation` (384 is the
default, 1536 four times finer).
"""

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # 2-core machine: threads slow large dense solves

import numpy as np  # noqa: E402
from harness import adapt, cycle_energy, cycles, ends, hertz_contact, increments, monotonic  # noqa: E402

import fretting as fr  # noqa: E402
from fretting.analysis.accuracy import BAND, traction_error  # noqa: E402
from fretting.models import galerkin as gk  # noqa: E402
from fretting.models.collocation import CollocationModel  # noqa: E402
from fretting.models.method4 import stick_zones  # noqa: E402
from fretting.physics import closed_forms as cf  # noqa: E402

CYCLE_STEPS = 4
CYCLE_PSI = (0.95, 0.8, 0.5, 0.3, 0.2, 0.1, 0.05, 0.01, 0.001, 1e-6)
CM_PSI = (0.05, 0.2, 0.5, 0.8, 0.95, 0.999, 0.999999)
MD_Q_END = (0.3, -0.2, -0.7)
TENSION_TAU = (0.3, 1.0, 2.5, 8.6)  # 8.6: c = 0.05 a
ROUNDED_PSI = (0.2, 0.5, 0.8)
CHEBYSHEV_NODES = (384, 1536)
HEADER = ("case", "rtol", "nodes", "passes", "energy", "ends /a", "q /fp0", "slip /max", "ms/step")


class _ChebyshevScene(CollocationModel):
    """The fixed-grid model with the two names the benchmark's loop reads."""

    def __init__(self, contact, nodes):
        super().__init__(contact, fr.models.Grid(nodes))

    @property
    def nodes(self):
        return self.grid.N


def timed(scene, Q, sigma=None, repeats=3):
    """Increments and the median wall time per increment [ms]."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        ds, g = increments(scene, Q, sigma)
        times.append(time.perf_counter() - start)
    return ds, g, 1e3 * np.median(times) / (len(Q) - 1)


def scenes(contact, Q, sigma, rtol, chebyshev):
    """(label, rtol, scene, passes) for the adapted Galerkin mesh and each Chebyshev grid."""
    scene, _, _, passes = adapt(contact, Q, sigma, rtol=rtol)
    yield "galerkin", f"{rtol:.0e}", scene, passes
    for nodes in CHEBYSHEV_NODES if chebyshev else ():
        yield f"chebyshev {nodes}", "-", _ChebyshevScene(contact, nodes), 1


def traction(scene, g, ds):
    """Nodal traction [Pa]: the Galerkin scene keeps Coulomb exactly where `ds` slipped."""
    return (
        g / (scene.pressure_scale * np.sqrt(1 - scene.t**2))
        if isinstance(scene, _ChebyshevScene)
        else scene.nodal_traction(g, ds)
    )


def stick_ends(scene, slip):
    if isinstance(scene, _ChebyshevScene):
        return scene.contact.centre + scene.contact.a * np.array(stick_zones(scene.grid.t, slip))
    return ends(scene, slip)


def row(case, label, rtol, scene, passes, ms, energy="", ends_error="", traction="", slip=""):
    fmt = lambda v: v if isinstance(v, str) else f"{v:.1e}"  # noqa: E731
    name = f"{case} [{label}]"
    cells = (
        name,
        rtol,
        str(scene.nodes),
        str(passes),
        fmt(energy),
        fmt(ends_error),
        fmt(traction),
        fmt(slip),
        f"{ms:.2f}",
    )
    print(f"{cells[0]:<34}" + "".join(f"{c:>11}" for c in cells[1:]), flush=True)


def cycle_cases(contact, rtol, chebyshev):
    fP = contact.f * contact.P
    for psi in CYCLE_PSI:
        Q = cycles(psi * fP, CYCLE_STEPS)
        exact = cf.mindlin_deresiewicz_energy(contact, psi * fP)
        for label, tol, scene, passes in scenes(contact, Q, None, rtol, chebyshev and psi >= 1e-3):
            ds, _, ms = timed(scene, Q)
            row(
                f"cycle {psi:g}",
                label,
                tol,
                scene,
                passes,
                ms,
                energy=abs(cycle_energy(scene, ds, CYCLE_STEPS) / exact - 1),
            )


def cattaneo_mindlin_cases(contact, rtol, chebyshev):
    fP, fp0, a = contact.f * contact.P, contact.f * contact.p0, contact.a
    for psi in CM_PSI:
        Q = monotonic(psi * fP)[0]
        b = cf.stick_half_width(contact, Q[-1])
        for label, tol, scene, passes in scenes(contact, Q, None, rtol, chebyshev):
            ds, g, ms = timed(scene, Q)
            slip, x = ds.sum(axis=0), scene.x
            found = stick_ends(scene, slip)
            ends_error = np.abs(found - [[-b, b]]).max() / a if found.shape == (1, 2) else np.inf
            q_exact = cf.cattaneo_mindlin_traction(contact, Q[-1], x)
            exact_slip = cf.cattaneo_mindlin_slip(contact, Q[-1], x)
            row(
                f"CM {psi:g}", label, tol, scene, passes, ms,
                ends_error=ends_error,
                traction=traction_error(x, traction(scene, g[-1], ds[-1]), q_exact, [-b, b], BAND * a) / fp0,
                slip=np.abs(slip - exact_slip).max() / exact_slip.max(),
            )  # fmt: skip


def mindlin_deresiewicz_cases(contact, rtol, chebyshev):
    fP, fp0, a = contact.f * contact.P, contact.f * contact.p0, contact.a
    Q_star = 0.8 * fP
    for Q_end in MD_Q_END:
        Q = np.concatenate([np.linspace(0, Q_star, 5), np.linspace(Q_star, Q_end * fP, 9)[1:]])
        c = a * np.sqrt(1 - (Q_star - Q_end * fP) / (2 * fP))
        b = cf.stick_half_width(contact, Q_star)
        for label, tol, scene, passes in scenes(contact, Q, None, rtol, chebyshev):
            ds, g, ms = timed(scene, Q)
            episode = ds[4:].sum(axis=0)
            found = stick_ends(scene, episode)
            ends_error = np.abs(found - [[-c, c]]).max() / a if found.shape == (1, 2) else np.inf
            q_exact = cf.mindlin_deresiewicz_traction(contact, Q_star, Q_end * fP, scene.x)
            q = traction(scene, g[-1], ds[-1])
            q_error = traction_error(scene.x, q, q_exact, [-c, c, -b, b], BAND * a) / fp0
            row(f"MD 0.8 -> {Q_end:g}", label, tol, scene, passes, ms, ends_error=ends_error, traction=q_error)


def tension_cases(contact, rtol, chebyshev):
    for tau in TENSION_TAU:
        sigma = tau * contact.f * contact.p0
        Q, sigmas = monotonic(0.0, sigma_end=sigma)
        c = cf.bulk_tension_stick_half_width(contact, sigma)
        for label, tol, scene, passes in scenes(contact, Q, sigmas, rtol, chebyshev):
            ds, _, ms = timed(scene, Q, sigmas)
            found = stick_ends(scene, ds.sum(axis=0))
            ends_error = np.abs(found - [[-c, c]]).max() / contact.a if found.shape == (1, 2) else np.inf
            row(f"tension {tau:g}", label, tol, scene, passes, ms, ends_error=ends_error)


def rounded_flat_cases(contact, rtol, chebyshev):
    rounded = fr.Contact(fr.RoundedFlat(1e-3, 0.02), contact.E_star, contact.f, contact.P)
    for psi in ROUNDED_PSI:
        Q = monotonic(psi * rounded.f * rounded.P)[0]
        c = cf.ciavarella_jaeger(rounded, Q[-1], np.zeros(1))[1].a
        for label, tol, scene, passes in scenes(rounded, Q, None, rtol, chebyshev):
            ds, g, ms = timed(scene, Q)
            found = stick_ends(scene, ds.sum(axis=0))
            ends_error = np.abs(found - [[-c, c]]).max() / rounded.a if found.shape == (1, 2) else np.inf
            q_exact = cf.ciavarella_jaeger(rounded, Q[-1], scene.x)[0]
            q = traction(scene, g[-1], ds[-1])
            q_error = traction_error(scene.x, q, q_exact, [-c, c], BAND * rounded.a) / (rounded.f * rounded.p0)
            row(f"rounded flat {psi:g}", label, tol, scene, passes, ms, ends_error=ends_error, traction=q_error)


def flat_punch_case(contact, rtol):
    punch = fr.Contact(fr.FlatPunch(1e-3), contact.E_star, contact.f, contact.P)
    Q = np.array([0.0, 0.5, 0.9, 0.999, 0.999999]) * punch.f * punch.P
    scene, _, _, passes = adapt(punch, Q, rtol=rtol)
    ds, _, ms = timed(scene, Q)
    row("flat punch to 0.999999 fP", "galerkin", f"{rtol:.0e}", scene, passes, ms, slip=float(np.abs(ds).max()))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rtol", type=float, nargs="+", default=[1e-3, gk.DEFAULT_RTOL])
    parser.add_argument("--no-chebyshev", action="store_true", help="skip the fixed-grid rows")
    options = parser.parse_args()
    contact = hertz_contact()
    print(f"{HEADER[0]:<34}" + "".join(f"{h:>11}" for h in HEADER[1:]))
    for rtol in options.rtol:
        chebyshev = not options.no_chebyshev and rtol == options.rtol[-1]
        cycle_cases(contact, rtol, chebyshev)
        cattaneo_mindlin_cases(contact, rtol, chebyshev)
        mindlin_deresiewicz_cases(contact, rtol, chebyshev)
        tension_cases(contact, rtol, chebyshev)
        rounded_flat_cases(contact, rtol, chebyshev)
        flat_punch_case(contact, rtol)


if __name__ == "__main__":
    main()
