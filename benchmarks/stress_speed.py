"""Time of `fretting.analysis.stress.field` on a 200 x 100 grid over a cycle of 64 steps, beside its error.

A Hertz contact (R = 50 mm, E = 210 GPa, nu = 0.3, f = 0.6, P = 100 N/mm) is loaded to Q* = 0.6 f P
and cycled once to -Q* and back in 64 steps. The field of the specimen over |x| <= 2a, z <= 2a is
timed (wall clock, best of `--repeats`) for the exact model (McEwen's closed forms), a Galerkin mesh
adapted to rtol = 1e-4 and the 384-node grid (piecewise-linear loads). The error is the largest over
`--samples` points and 8 steps of the cycle, against a scipy quad of Johnson's eq 2.23 over the
Mindlin-Deresiewicz traction (Cattaneo-Mindlin with Masing's rule, `closed_forms`), relative to p0;
the quadrature is split at the ends of the stick zones, and its agreement with the exact model bounds
its own error (scipy's warnings on roundoff are silenced).

    python benchmarks/stress_speed.py [--repeats 3] [--samples 12]
"""

import argparse
import functools
import time
import warnings

import numpy as np
from scipy import integrate

import fretting as fr
from fretting.analysis import stress
from fretting.physics import closed_forms as cf

CONTACT = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)
NU = 0.3
STEPS = 64


def history():
    """Loading to Q* in 16 steps, then one cycle Q* -> -Q* -> Q* in `STEPS` steps."""
    Q_star = 0.6 * CONTACT.f * CONTACT.P
    return fr.History.piecewise_linear([0.0, Q_star, -Q_star, Q_star], None, [16, STEPS // 2, STEPS // 2])


def reference_traction(Q_star, Q, falling, x):
    """Mindlin-Deresiewicz traction [Pa] on body 1 in the cycle: unloading from Q*, or reloading from -Q*."""
    return cf.mindlin_deresiewicz_traction(CONTACT, Q_star if falling else -Q_star, Q, x)


def kinks(Q_star, Q):
    """Ends [m] of the stick zones of the Mindlin-Deresiewicz traction, where it has a vertical tangent."""
    ends = [cf.stick_half_width(CONTACT, load) for load in (Q_star, (Q_star - abs(Q)) / 2, (Q_star + abs(Q)) / 2)]
    return [sign * end for end in ends for sign in (-1, 1)]


def quadrature(traction, x, z, breaks):
    """``[sigma_xx, sigma_zz, tau_xz]`` [Pa] of the specimen (body 2: traction -q) by scipy quad of eq 2.23,
    split at `breaks` [m] and `x`."""
    a = CONTACT.a
    p = lambda s: float(CONTACT.pressure(np.array([s]))[0])  # noqa: E731
    t_x = lambda s: -float(traction(np.array([s]))[0])  # noqa: E731
    kernels = {
        "zu2": lambda u: z * u**2,
        "z3": lambda u: z**3,
        "z2u": lambda u: z**2 * u,
        "u3": lambda u: u**3,
    }

    def integral(load, kernel):
        value = integrate.quad(
            lambda s: load(s) * kernel(x - s) / ((x - s) ** 2 + z**2) ** 2,
            -a,
            a,
            points=[x, *breaks],
            limit=800,
            epsabs=1e-6,
            epsrel=1e-13,
        )[0]
        return -(2 / np.pi) * value

    k = {name: (integral(p, kernel), integral(t_x, kernel)) for name, kernel in kernels.items()}
    return np.array([k["zu2"][0] + k["u3"][1], k["z3"][0] + k["z2u"][1], k["z2u"][0] + k["zu2"][1]])


def timed(result, x, z, repeats):
    """Best wall-clock time [s] of the field of the last `STEPS` + 1 recorded steps, and the field."""
    steps = result.step.values[-(STEPS + 1) :]
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        field = stress.field(result, x, z, step=steps, nu=NU)
        best = min(best, time.perf_counter() - start)
    return best, field


def error(result, field, samples, rng):
    """Largest error / p0 of `field` over `samples` points at 8 steps of the cycle, against `quadrature`."""
    Q_star = float(result.Q.max())
    steps = field.step.values[:: STEPS // 8][1:]
    worst = 0.0
    for step in steps:
        row = int(np.searchsorted(result.step.values, step))
        Q, falling = float(result.Q[row]), float(result.Q[row - 1]) > float(result.Q[row])
        traction = functools.partial(reference_traction, Q_star, Q, falling)
        columns, rows = rng.integers(0, field.sizes["x"], samples), rng.integers(1, field.sizes["z"], samples)
        for i, j in zip(columns, rows, strict=True):
            x, z = float(field.x[i]), float(field.z[j])
            reference = quadrature(traction, x, z, kinks(Q_star, Q))
            got = [float(field[name].sel(step=step)[j, i]) for name in ("sigma_xx", "sigma_zz", "tau_xz")]
            worst = max(worst, float(np.abs(np.array(got) - reference).max()) / CONTACT.p0)
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--samples", type=int, default=12)
    args = parser.parse_args()
    warnings.simplefilter("ignore", integrate.IntegrationWarning)
    a = CONTACT.a
    x, z = np.linspace(-2 * a, 2 * a, 200), np.linspace(0, 2 * a, 100)
    loads = history()
    print(f"stress field of the specimen: {x.size} x {z.size} points, {STEPS + 1} steps (one cycle and its start)")
    print(f"{'model':<46} {'nodes':>6} {'time [s]':>9} {'error / p0':>11}")
    for label, spec in (
        ("exact (McEwen)", fr.models.Exact()),
        ("Galerkin mesh, rtol 1e-4", fr.models.Mesh(rtol=1e-4)),
        ("Gauss-Chebyshev grid", fr.models.Grid(384)),
    ):
        result = fr.simulate(CONTACT, loads, spec)
        seconds, field = timed(result, x, z, args.repeats)
        worst = error(result, field, args.samples, np.random.default_rng(1))
        kind = field.attrs["traction"]
        print(f"{label + f' [{kind}]':<46} {result.sizes['x']:>6} {seconds:>9.3f} {worst:>11.2e}")


if __name__ == "__main__":
    main()
