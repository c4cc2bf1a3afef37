"""Speed of `fretting.analysis.fatigue.apply` over a field, beside the error of its plane search.

The field is a non-proportional plane-strain stress history on a ``z`` x ``x`` grid (three harmonics
with random amplitudes, phases and means at each point: no contact solution is needed to time the
criteria). For each critical-plane criterion the script prints the wall time of `apply` and the
largest relative difference, over `--check` points, between its parameter and a search written here
independently: the formulas of the criterion evaluated on `--planes` in-plane normals evenly spaced
over 180 degrees (SWT, Findley, Fatemi-Socie), or the exact plane of largest shear amplitude (MWCM,
`mwcm_exact`). The brute force can only fall short of the true maximum (by ``O((pi / planes)^2)``
relative to the curvature), so "short" below 0 says `apply` found less.

    python benchmarks/fatigue_criteria.py [--nz 100 --nx 200 --steps 64 --check 200 --planes 36000]
"""

import argparse
import time

import numpy as np
import xarray as xr

from fretting.analysis.fatigue import CRITERIA, Material, apply

MATERIAL = Material(E=210e9, nu=0.3, sigma_limit=500e6, tau_limit=320e6, fs_k=0.6, sigma_y=1e9)


def field(nz, nx, steps, seed=0):
    """A Dataset of ``sigma_xx``, ``sigma_zz``, ``tau_xz`` [Pa] on ``(step, z, x)``."""
    rng = np.random.default_rng(seed)
    t = 2 * np.pi * np.arange(steps)[:, None, None] / steps
    stresses = {}
    for name in ("sigma_xx", "sigma_zz", "tau_xz"):
        harmonics = sum(rng.normal(0, 100e6, (nz, nx)) * np.sin(n * t + rng.uniform(0, 7, (nz, nx))) for n in (1, 2, 3))
        stresses[name] = (("step", "z", "x"), rng.normal(0, 50e6, (nz, nx)) + harmonics)
    return xr.Dataset(stresses, coords={"z": np.linspace(0, 1e-3, nz), "x": np.linspace(-1e-3, 1e-3, nx)})


def brute_force(criterion, xx, zz, xz, planes):
    """The criterion's parameter at one point by exhaustive search: normals at ``phi_j = pi j / planes``."""
    if criterion == "mwcm":
        return mwcm_exact(xx, zz, xz)
    nu, E = MATERIAL.nu, MATERIAL.E
    phi = np.pi * np.arange(planes) / planes
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    sigma_n = xx * c * c + zz * s * s + 2 * xz * s * c
    tau = (zz - xx) * s * c + xz * (c * c - s * s)
    trace = (1 + nu) * (xx + zz)  # plane strain: sigma_yy = nu (sigma_xx + sigma_zz)
    eps_a = np.ptp((1 + nu) * sigma_n - nu * trace, axis=1) / 2 / E
    sigma_n_max, tau_a = sigma_n.max(axis=1), np.ptp(tau, axis=1) / 2
    if criterion == "swt":
        return np.max(sigma_n_max * eps_a)
    if criterion == "findley":
        return np.max(tau_a + MATERIAL.findley_constant() * sigma_n_max)
    G = E / (2 * (1 + nu))
    return np.max(tau_a / G / 2 * (1 + MATERIAL.fs_k * sigma_n_max / MATERIAL.sigma_y))


def mwcm_exact(xx, zz, xz):
    """The MWCM parameter at one point on its exact plane (the brute force reads sigma_n,max off its grid).

    ``tau(phi) = tau_xz cos 2 phi - h sin 2 phi``, ``h = (sigma_xx - sigma_zz) / 2``: between instants i and j
    it changes by ``|(dh, dtau_xz)| cos(2 phi - atan2(-dh, dtau_xz))``, so ``tau_a`` is largest, half the
    longest chord of the path ``(h, tau_xz)``, on ``phi = atan2(-dh, dtau_xz) / 2`` of the longest chord and on
    its conjugate ``phi + pi/2``; the plane is the one of the two with the larger ``sigma_n,max``.
    """
    h = (xx - zz) / 2
    dh, dxz = h[:, None] - h[None, :], xz[:, None] - xz[None, :]
    i, j = np.unravel_index(np.argmax(dh**2 + dxz**2), dh.shape)
    tau_a = np.hypot(dh[i, j], dxz[i, j]) / 2
    phi = np.arctan2(-dh[i, j], dxz[i, j]) / 2 + np.array([0, np.pi / 2])[:, None]
    sigma_n_max = np.max((xx + zz) / 2 + h * np.cos(2 * phi) + xz * np.sin(2 * phi), axis=1).max()
    kappa, _ = MATERIAL.mwcm_constants()
    return tau_a + kappa * sigma_n_max / tau_a


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nz", type=int, default=100)
    parser.add_argument("--nx", type=int, default=200)
    parser.add_argument("--steps", type=int, default=64)
    parser.add_argument("--check", type=int, default=200, help="points checked by brute force")
    parser.add_argument("--planes", type=int, default=36000, help="normals of the brute-force search")
    args = parser.parse_args()
    data = field(args.nz, args.nx, args.steps)
    points = np.random.default_rng(1).choice(args.nz * args.nx, args.check, replace=False)
    print(f"grid {args.nz} x {args.nx}, {args.steps} steps; brute force on {args.check} points, {args.planes} planes")
    print(f"{'criterion':>13} {'time [s]':>9} {'max |rel diff|':>15} {'worst short':>12}")
    for criterion in CRITERIA:
        start = time.perf_counter()
        maps = apply(data, criterion, MATERIAL)
        elapsed = time.perf_counter() - start
        if "phi" not in maps:  # a criterion on no plane: nothing to search
            print(f"{criterion:>13} {elapsed:9.2f} {'(invariant)':>15}")
            continue
        found = maps.parameter.values.ravel()[points]
        at = [data[name].values.reshape(args.steps, -1)[:, points].T for name in ("sigma_xx", "sigma_zz", "tau_xz")]
        reference = np.array([brute_force(criterion, *(s[k] for s in at), args.planes) for k in range(args.check)])
        relative = (found - reference) / np.abs(reference)
        print(f"{criterion:>13} {elapsed:9.2f} {np.abs(relative).max():15.2e} {relative.min():12.2e}")


if __name__ == "__main__":
    main()
