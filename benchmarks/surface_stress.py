"""Error at every node and cost of `fretting.analysis.nucleation.surface_stress` on the exact and discretised models.

A Hertz contact (R = 50 mm, E = 210 GPa, nu = 0.3, f = 0.6, P = 100 N/mm) under the default model, the
default Galerkin mesh, the default grid and the 96-node grid: the largest error at any node, relative
to p0, against Cattaneo-Mindlin at Q = 0.5 f P and Nowell-Hills at Q = 0.5 f P with sigma = 0.2 f p0 in
phase (McEwen's surface stress of their elliptical loads), with where it lies, ``(x - e) / b``; for a
discretised model also the error of its nodal tractions alone (the stick flags cleared, so that no
stick end is fitted: `fretting.physics.surface.SurfaceStress.at_stick_ends`). Then the same on
Mindlin-Deresiewicz unloading, Q from 0 to 0.5 f P and back to 0.1 f P (McEwen's stress of
``q_CM(0.5 f P) - 2 q_CM(0.2 f P)``), also on the varying-load model (the contact formed at P / 2 and
pressed to P with no shear first), the largest error split by where it lies: within `NEAR` node
spacings of the stick end the loading left (``c*``, now inside the stick zone, a kink of the locked-in
slip: fitted, `fretting.physics.surface.kinks`), of the current stick end (``c'``, fitted), and
the contact's edges, elsewhere, and about ``c'`` with the exact slip fitted instead of the model's.
Then on random walks of ``Q``, against Masing's elliptical loads at the model's nodes, the largest error
at each step (median, 90th percentile and largest over the steps), with the kinks that earlier turning
points left fitted where they stand apart and without them, and the steps the fit makes worse. Then the
wall-clock time
(best of `--repeats`) of `fretting.simulate`, whose engine tallies the per-cycle peaks of the surface
stress, and of `surface_stress` on four histories, under the default model and the default grid: 20
sine cycles of 64 steps at 0.5 f P, a random walk of 400 segments of 8 steps within 0.8 f P, 200
cycles of in-phase Q and sigma, and 20 cycles of Q and sigma 90 degrees out of phase (the default model
there is the Galerkin mesh). Run it on two checkouts to compare them:

    python benchmarks/surface_stress.py [--repeats 3]
"""

import argparse
import timeit

import numpy as np

import fretting as fr
from fretting.analysis import nucleation
from fretting.physics import closed_forms as cf
from fretting.physics import surface
from fretting.physics.surface import ellipse_stress

CONTACT = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


def ellipse_transform(x, centre, half_width):
    """``-(2/pi) PV int sqrt(1 - ((s - centre)/half_width)^2) / (x - s) ds`` [-] (McEwen at the surface)."""
    d = x - centre
    return -2 * (d - np.sign(d) * np.sqrt(np.clip(d**2 - half_width**2, 0, None))) / half_width


def partial_slip_stress(x, b, e=0.0):
    """The surface stress [f p0] of body 1 at `x` [m] of the traction of Cattaneo-Mindlin (`e` = 0) or of
    Nowell-Hills, ``f p0 (sqrt(1 - x^2/a^2) - (b/a) sqrt(1 - (x - e)^2/b^2))``, stick zone `b` [m] about `e` [m]."""
    a = CONTACT.a
    return ellipse_transform(x, 0.0, a) - b / a * ellipse_transform(x, e, b)


def closed_form_error(tau, model):
    """Largest error [p0] of body 1's surface stress at Q = 0.5 f P with sigma = tau f p0 in phase, where it
    lies, ``(x - e) / b``, and the error of the nodal tractions alone (NaN for an exact model)."""
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    Q, sigma = 0.5 * fP, tau * fp0
    result = fr.simulate(CONTACT, fr.History.piecewise_linear([0.0, Q], [0.0, sigma], 4), model)
    x = result.x.values
    b, e = cf.stick_half_width(CONTACT, Q), cf.nowell_hills_offset(CONTACT, sigma)
    expected = -CONTACT.pressure(x) + fp0 * partial_slip_stress(x, b, e)
    error = np.abs(nucleation.surface_stress(result, body=1).values[-1] - expected)
    nodal = np.nan
    if result.attrs["model"] in ("grid", "mesh"):
        cleared = result.assign(stick=(("step", "x"), np.zeros(result.stick.shape, dtype=bool)))
        nodal = np.abs(nucleation.surface_stress(cleared, body=1).values[-1] - expected).max() / CONTACT.p0
    return result.attrs["model"], x.size, error.max() / CONTACT.p0, (x[error.argmax()] - e) / b, nodal


#: Node spacings about a stick end or an edge within which `unloading_error` counts an error as that point's (`near`):
#: the fit of `fretting.physics.surface.gradients` spans as many.
NEAR = 6


def near(x, point):
    """The nodes `x` [m] within `NEAR` spacings, those of the nodes about it, of ``-point`` or ``point`` [m]."""
    close = np.zeros(x.size, dtype=bool)
    for at in (-point, point):
        i = int(np.clip(np.searchsorted(x, at), 1, x.size - 1))
        close |= np.abs(x - at) < NEAR * (x[i] - x[i - 1])
    return close


def unloading_error(model, grown=False):
    """Model, nodes and the largest errors [p0] of body 1's surface stress after Mindlin-Deresiewicz unloading
    from ``Q* = 0.5 f P`` to ``Q = 0.1 f P``: about the former stick end ``c*``, about the current one ``c'``,
    about the contact's edges, elsewhere (`NEAR` spacings), and about ``c'`` again with the model's slip at the
    last step replaced by the exact one (``s_CM(Q*) - 2 s_CM((Q* - Q) / 2)``,
    `fretting.physics.closed_forms.cattaneo_mindlin_slip`), which tells the fit's error from that of the
    model's slip. `grown`: the contact formed at ``P / 2`` and pressed to ``P`` first with no shear, which
    leaves no traction (a varying ``P``: `fretting.models.Varying`, or the default there, `fretting.models.Jaeger`)."""
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    Q_star, Q = 0.5 * fP, 0.1 * fP
    if grown:
        formed = fr.Contact(CONTACT.profile, CONTACT.E_star, CONTACT.f, CONTACT.P / 2)
        P = [CONTACT.P / 2] + [CONTACT.P] * 3
        result = fr.simulate(formed, fr.History.piecewise_linear([0.0, 0.0, Q_star, Q], None, 8, P=P), model)
    else:
        result = fr.simulate(CONTACT, fr.History.piecewise_linear([0.0, Q_star, Q], None, 8), model)
    x = result.x.values
    c_star, c = cf.stick_half_width(CONTACT, Q_star), cf.stick_half_width(CONTACT, (Q_star - Q) / 2)
    expected = -CONTACT.pressure(x) + fp0 * (partial_slip_stress(x, c_star) - 2 * partial_slip_stress(x, c))
    slip = result.slip.values.copy()
    slip[-1] = cf.cattaneo_mindlin_slip(CONTACT, Q_star, x) - 2 * cf.cattaneo_mindlin_slip(CONTACT, (Q_star - Q) / 2, x)
    errors = [
        np.abs(nucleation.surface_stress(run, body=1).values[-1] - expected) / CONTACT.p0
        for run in (result, result.assign(slip=(result.slip.dims, slip)))
    ]
    former, current, edges = (near(x, point) for point in (c_star, c, CONTACT.a))
    model_slip, exact_slip = errors
    elsewhere = model_slip[~(former | current | edges)].max()
    return (
        result.attrs["model"],
        x.size,
        [model_slip[former].max(), model_slip[current].max(), model_slip[edges].max(), elsewhere],
        exact_slip[current].max(),
    )


def walk_errors(model, seed=1, turns=60, steps=8):
    """Model, nodes, and the largest error [p0] of body 1's surface stress at each step of a random walk of ``Q``
    within 0.8 f P (`turns` segments of `steps` steps) against Masing's elliptical loads (the exact model's, by
    `fretting.analysis.nucleation.elliptical_traction`) summed at the model's nodes, with the kinks that earlier
    turning points left in the slip fitted (`fretting.physics.surface.kinks`) and without."""
    fP = CONTACT.f * CONTACT.P
    walk = np.concatenate([[0.0], np.random.default_rng(seed).uniform(-0.8, 0.8, turns) * fP])
    history = fr.History.piecewise_linear(walk, None, steps)
    widths, centres, loads = nucleation.elliptical_traction(fr.simulate(CONTACT, history))
    result = fr.simulate(CONTACT, history, model)
    x = result.x.values
    expected = loads @ ellipse_stress(x / CONTACT.a, widths[:, None], centres[:, None]) - CONTACT.pressure(x)
    errors = [np.abs(nucleation.surface_stress(result, body=1).values - expected).max(axis=1) / CONTACT.p0]
    kink, surface.KINK = surface.KINK, np.inf
    try:
        errors.append(np.abs(nucleation.surface_stress(result, body=1).values - expected).max(axis=1) / CONTACT.p0)
    finally:
        surface.KINK = kink
    return result.attrs["model"], x.size, errors


def histories():
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    walk = np.concatenate([[0.0], np.random.default_rng(1).uniform(-0.8, 0.8, 400) * fP])
    return {
        "sine, 20 x 64 steps": fr.History.sinusoidal(0.5 * fP, cycles=20, steps_per_cycle=64),
        "random walk, 400 x 8 steps": fr.History.piecewise_linear(walk, None, 8),
        "in phase, 200 x 64 steps": fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, cycles=200, steps_per_cycle=64),
        "90-degree ellipse, 20 x 32 steps": fr.History.sinusoidal(
            0.4 * fP, 0.3 * fp0, cycles=20, steps_per_cycle=32, phase_deg=90.0
        ),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    repeats = parser.parse_args().repeats
    for model in (None, fr.models.Mesh(), fr.models.Grid(), fr.models.Grid(96)):
        for tau in (0.0, 0.2):
            name, nodes, error, where, nodal = closed_form_error(tau, model)
            alone = "" if np.isnan(nodal) else f"; nodal tractions alone {nodal:.2e} p0"
            print(
                f"{name:8s} {nodes:5d} nodes, sigma = {tau} f p0: largest error {error:.2e} p0 at (x - e) / b = "
                f"{where:.4f}{alone}"
            )
    print("Mindlin-Deresiewicz unloading, 0.5 f P to 0.1 f P: largest error [p0] by where it lies")
    models = [(model, False) for model in (None, fr.models.Mesh(), fr.models.Grid(), fr.models.Grid(1536))]
    for model, grown in models + [(fr.models.Varying(), True), (None, True)]:  # the default grown: Jaeger's
        name, nodes, errors, fitted = unloading_error(model, grown)
        where = ", ".join(f"{e:.2e} ({w})" for e, w in zip(errors, ("c*", "c'", "edges", "elsewhere"), strict=True))
        grew = " (the contact grown from P / 2 first)" if grown else ""
        print(f"{name:8s} {nodes:5d} nodes{grew}: {where}; {fitted:.2e} (c', the exact slip fitted)")
    print("random walks of Q, 60 x 8 steps: largest error [p0] at a step, median / 90 % / largest over the steps")
    for model in (fr.models.Mesh(), fr.models.Grid(), fr.models.Grid(1536)):
        for seed in (1, 2, 3):
            name, nodes, (fitted, unfitted) = walk_errors(model, seed)
            figures = [" / ".join(f"{v:.2e}" for v in np.percentile(e, [50, 90, 100])) for e in (fitted, unfitted)]
            worse = fitted - unfitted
            print(
                f"{name:8s} {nodes:5d} nodes, seed {seed}: {figures[0]}; without the kinks {figures[1]}; "
                f"{np.count_nonzero(worse > 1e-3)} of {worse.size} steps worse by over 1e-3 (at most {worse.max():.1e})"
            )
    for model in (None, fr.models.Grid()):
        for name, history in histories().items():
            result = fr.simulate(CONTACT, history, model)
            run = min(timeit.repeat(lambda h=history, m=model: fr.simulate(CONTACT, h, m), number=1, repeat=repeats))
            stress = min(timeit.repeat(lambda r=result: nucleation.surface_stress(r), number=1, repeat=repeats))
            size = f"{result.sizes['step']} steps x {result.sizes['x']} nodes"
            print(f"{name} ({result.attrs['model']}, {size}): simulate {run:.3f} s, surface_stress {stress:.3f} s")


if __name__ == "__main__":
    main()
