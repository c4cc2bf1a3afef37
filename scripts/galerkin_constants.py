"""The comparisons behind the tuning constants of `fretting.models.galerkin`, for its validation page.

Imported by scripts/make_validation.py (``--only galerkin-constants``), which stamps and writes
docs/validation/galerkin-constants.md. Each section reruns, on the scenes of
benchmarks/galerkin_convergence.py (its Hertz contact, its histories, the adaptive loop of
`harness.adapt`), the comparison that one constant's comment relies on: the constant's value
against another, every other constant as shipped.
"""

import contextlib
import warnings

import numpy as np
from harness import adapt, cycle_energy, cycles, hertz_contact, monotonic
from scipy import integrate

import fretting as fr
from fretting.analysis.accuracy import BAND, traction_error
from fretting.models import galerkin as gk
from fretting.models.galerkin import kernels, mesh, quadrature
from fretting.physics import closed_forms as cf

#: Increments per segment of the cycles ``Q = +-psi f P`` (as in benchmarks/galerkin_convergence.py).
CYCLE_STEPS = 4
#: Amplitudes ``Q*/(f P)`` of the cycles, over the range `BOUNDARY_ERROR` was fitted to.
CYCLE_PSI = (0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 0.95)
#: Loads ``Q/(f P)`` close to sliding, whose stick zone is small and slip zones large.
NEAR_SLIDING_PSI = (0.8, 0.95, 0.999, 0.999999)
#: Loads ``Q/(f P)`` whose slip zones are small.
SMALL_ZONE_PSI = (0.05, 0.2)
#: Loads ``Q/(f P)`` whose traction is scored next to the stick ends, graded elements around them.
GRADED_PSI = (0.2, 0.5, 0.8)
#: Amplitudes and tolerances of the energy left inside zones held at `ZONE_ELEMENTS` elements.
FLOOR_PSI = (0.2, 0.5)
FLOOR_RTOL = (1e-4, 1e-5)
#: Tolerances of the cycles' energy.
RTOLS = (1e-3, gk.DEFAULT_RTOL)
#: Ratios of the geometric pieces compared with `GRADING_RATIO`.
GRADING_RATIOS = (quadrature.GRADING_RATIO, 0.75, 0.9)
#: Rounded flat whose friction limits are integrated (b = 1 mm, R = 20 mm, as in the benchmark).
ROUNDED_FLAT = (1e-3, 0.02)


def _owner(name):
    """The module of `fretting.models.galerkin` that defines the constant `name`."""
    return next(module for module in (kernels, quadrature, mesh) if name in vars(module))


@contextlib.contextmanager
def overridden(**values):
    """Set constants of `fretting.models.galerkin` for the block, and restore them after it."""
    before = {name: getattr(_owner(name), name) for name in values}
    for name, value in values.items():
        setattr(_owner(name), name, value)
    try:
        yield
    finally:
        for name, value in before.items():
            setattr(_owner(name), name, value)


def cycle_error(contact, psi, rtol):
    """``|W/W_ref - 1|`` of the second cycle of ``Q = +-psi f P`` on its adapted mesh, and the mesh's nodes.

    ``W_ref`` is the energy per cycle of Mindlin & Deresiewicz.
    """
    Q_star = psi * contact.f * contact.P
    scene, ds, _, _ = adapt(contact, cycles(Q_star, CYCLE_STEPS), rtol=rtol)
    return abs(cycle_energy(scene, ds, CYCLE_STEPS) / cf.mindlin_deresiewicz_energy(contact, Q_star) - 1), scene.nodes


def cattaneo_mindlin_errors(contact, psi, grading):
    """Slip [/max] and traction [f p0] errors of ``Q = psi f P`` in 4 increments at `DEFAULT_RTOL`, and the nodes.

    Against Cattaneo-Mindlin, on the mesh of `harness.adapt` graded around the boundaries by `grading`.
    """
    Q = monotonic(psi * contact.f * contact.P)[0]
    scene, ds, g, _ = adapt(contact, Q, rtol=gk.DEFAULT_RTOL, grading=grading)
    b = cf.stick_half_width(contact, Q[-1])
    slip = cf.cattaneo_mindlin_slip(contact, Q[-1], scene.x)
    q = cf.cattaneo_mindlin_traction(contact, Q[-1], scene.x)
    q_found = scene.nodal_traction(g[-1], ds[-1])
    return (
        np.abs(ds.sum(axis=0) - slip).max() / np.abs(slip).max(),
        traction_error(scene.x, q_found, q, [-b, b], BAND * contact.a) / (contact.f * contact.p0),
        scene.nodes,
    )


def rtol_section(contact, table):
    header = ("Q*/fP", *(f"rtol {rtol:.0e}: error [nodes]" for rtol in RTOLS))
    rows, worst = [], dict.fromkeys(RTOLS, 0.0)
    for psi in CYCLE_PSI:
        cells = []
        for rtol in RTOLS:
            error, nodes = cycle_error(contact, psi, rtol)
            worst[rtol] = max(worst[rtol], error / rtol)
            cells.append(f"{error:.1e} [{nodes}]")
        rows.append((psi, *cells))
    summary = ", ".join(f"{value:.2f} at rtol {rtol:.0e}" for rtol, value in worst.items())
    return (
        "## DEFAULT_RTOL\n\n"
        f"The relative error `|W/W_ref - 1|` of the energy dissipated in the second cycle of `Q = +-Q*`\n"
        f"({CYCLE_STEPS} increments a segment) on the mesh adapted to it, against Mindlin & Deresiewicz, and\n"
        f"the mesh's nodes. `DEFAULT_RTOL` is {gk.DEFAULT_RTOL:.0e}. Worst error over rtol: {summary}.\n\n"
        + table(header, rows)
    )


def boundary_section(contact, table):
    values = (mesh.BOUNDARY_ERROR, mesh.BOUNDARY_ERROR / 4)
    rows = []
    for value in values:
        with overridden(BOUNDARY_ERROR=value):
            rows.append(
                (
                    f"{value:g}",
                    *(f"{max(cycle_error(contact, psi, rtol)[0] for psi in CYCLE_PSI) / rtol:.2f}" for rtol in RTOLS),
                )
            )
    return (
        "## BOUNDARY_ERROR\n\n"
        f"The worst relative error of the cycles' energy above (Q*/fP in {list(CYCLE_PSI)}) over rtol,\n"
        f"with `BOUNDARY_ERROR` as shipped ({mesh.BOUNDARY_ERROR:g}) and a quarter of it (elements holding a\n"
        "boundary about 1.7 times as large). Above 1, some cycle misses the accuracy asked.\n\n"
        + table(("BOUNDARY_ERROR", *(f"worst error / rtol, rtol {rtol:.0e}" for rtol in RTOLS)), rows)
    )


def cattaneo_mindlin_section(contact, table, name, alternatives, loads, why, recorded=False):
    """The errors of `cattaneo_mindlin_errors` with the constant `name` as shipped and at each of `alternatives`, on
    the energy's mesh (`ENERGY_GRADING`), or where `recorded`, graded as for a recorded step (`BOUNDARY_GRADING`,
    read under the override)."""
    rows = []
    for value in (getattr(_owner(name), name), *alternatives):
        with overridden(**{name: value}):
            grading = mesh.BOUNDARY_GRADING if recorded else mesh.ENERGY_GRADING
            for psi in loads:
                slip, q, nodes = cattaneo_mindlin_errors(contact, psi, grading)
                rows.append((value, psi, nodes, f"{slip:.1e}", f"{q:.1e}"))
    graded = "as for a recorded step (`BOUNDARY_GRADING`)" if recorded else "as for the energy (`ENERGY_GRADING`)"
    return (
        f"## {name}\n\n"
        f"Cattaneo-Mindlin: `Q = psi f P` in 4 increments on the mesh adapted at rtol {gk.DEFAULT_RTOL:.0e},\n"
        f"graded around the stick ends {graded}, {why};\n"
        f"`{name}` as shipped ({getattr(_owner(name), name)}) and {' and '.join(map(str, alternatives))}. "
        "Slip error relative to the largest slip;\n"
        f"traction error in f p0 away from {BAND} a of the stick ends and the edges.\n\n"
        + table((name, "Q/fP", "nodes", "slip", "traction"), rows)
    )


def zone_floor_section(contact, table):
    rows = []
    for label, zone_error in (("as shipped", mesh.ZONE_ERROR), (f"held at {mesh.ZONE_ELEMENTS}", np.finfo(float).tiny)):
        with overridden(ZONE_ERROR=zone_error):
            for psi in FLOOR_PSI:
                cells = (
                    f"{error:.1e} [{nodes}]" for error, nodes in (cycle_error(contact, psi, r) for r in FLOOR_RTOL)
                )
                rows.append((label, psi, *cells))
    return (
        "## ZONE_ERROR\n\n"
        f"`zone_fraction` makes zones finer than `ZONE_ELEMENTS` ({mesh.ZONE_ELEMENTS}) elements once rtol is below\n"
        f"`ZONE_ERROR` ({mesh.ZONE_ERROR:.0e}). The cycles' energy error [nodes] as above, with that refinement as\n"
        f"shipped and with the zones held at `ZONE_ELEMENTS` elements (the boundary elements still follow rtol):\n"
        "the energy error left inside zones of `ZONE_ELEMENTS` elements is at most the latter.\n\n"
        + table(("zone elements", "Q*/fP", *(f"rtol {rtol:.0e}" for rtol in FLOOR_RTOL)), rows)
    )


def limits_error(contact, ratio):
    """Largest error of the friction limits ``L_k`` of the initial mesh against adaptive quadrature [/max L_k]."""
    with overridden(GRADING_RATIO=ratio):
        theta = gk.initial_theta()
        scene = gk.Mesh(theta=theta).build(contact)
    profile, corners = contact.profile, np.arccos(contact.profile.b / contact.a)
    hats = np.eye(theta.size)

    def integrand(angle, k):
        p = profile.pressure(np.atleast_1d(np.cos(angle)), contact.a, contact.centre, contact.P, contact.E_star)[0]
        return contact.f * contact.a * p * np.sin(angle) * np.interp(angle, theta, hats[k])

    reference = np.empty(theta.size)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)  # rounding near the limits' zeros
        for k in range(theta.size):
            low, high = theta[max(k - 1, 0)], theta[min(k + 1, theta.size - 1)]
            points = [p for p in (theta[k], corners, np.pi - corners) if low < p < high] or None
            reference[k] = integrate.quad(
                integrand, low, high, args=(k,), points=points, epsabs=0, epsrel=1e-12, limit=500
            )[0]
    reference = reference[::-1]  # theta descending: the scene's x ascending
    return np.abs(scene.limit - reference).max() / np.abs(reference).max()


def grading_section(table):
    contact = fr.Contact(fr.RoundedFlat(*ROUNDED_FLAT), 115e9, 0.6, 1e5)
    rows = [(ratio, f"{limits_error(contact, ratio):.1e}") for ratio in GRADING_RATIOS]
    return (
        "## GRADING_RATIO\n\n"
        "The friction limits `L_k = int f p phi_k dx` of the initial mesh on a rounded flat (b = 1 mm,\n"
        "R = 20 mm, E* = 115 GPa, f = 0.6, P = 100 N/mm), whose pressure has a singular derivative at the\n"
        "ends of the flat, by 8-point Gauss on pieces graded toward them with each ratio, against adaptive\n"
        "quadrature (scipy `quad`, split at the ends and the nodes, relative tolerance 1e-12): the largest\n"
        "error relative to the largest limit.\n\n" + table(("GRADING_RATIO", "error"), rows)
    )


def body(table):
    """The page's text below its stamp; ``table(header, rows)`` writes a markdown table."""
    contact = hertz_contact()
    sections = (
        rtol_section(contact, table),
        boundary_section(contact, table),
        cattaneo_mindlin_section(
            contact, table, "INITIAL_ELEMENTS", (mesh.INITIAL_ELEMENTS // 2,), NEAR_SLIDING_PSI, "close to sliding"
        ),
        cattaneo_mindlin_section(
            contact, table, "ZONE_ELEMENTS", (mesh.ZONE_ELEMENTS // 2,), SMALL_ZONE_PSI, "small slip zones"
        ),
        cattaneo_mindlin_section(
            contact,
            table,
            "BOUNDARY_GRADING",
            (2 * mesh.BOUNDARY_GRADING, mesh.BOUNDARY_GRADING / 2),
            GRADED_PSI,
            "the stick zone next to the ends",
            recorded=True,
        ),
        zone_floor_section(contact, table),
        grading_section(table),
    )
    intro = (
        "Each section reruns the comparison behind one tuning constant of `fretting.models.galerkin`,\n"
        "the constant as shipped against another value, every other constant as shipped. The scenes are\n"
        "those of `benchmarks/galerkin_convergence.py`: a Hertz contact (R = 50 mm, E = 210 GPa,\n"
        "nu = 0.3, P = 100 N/mm, f = 0.6), each history's mesh adapted by the loop of `harness.adapt`\n"
        "from `initial_theta()`, scored against the closed forms."
    )
    return "\n\n".join((intro, *sections))
