"""Convergence and speed of the model of a varying normal load (`fretting.models.Varying`).

A random walk of (P, Q, sigma) on the Hertz scene of benchmarks/engine_speed.py (P between 0.7
and 1.3 of the contact's, Q within 0.4 f P0, sigma within 0.4 f p0, independent draws, 16 steps
per segment) is run on 64 to 512 cells (the default) at the default ``load_part``, then on the
default cells with coarser parts of the increments. For each the script prints the CPU
time (best of `--repeats`), the total energy, its relative error and the largest error of the
stick-zone ends at the vertices (in the half-width of each vertex's contact), both against a run
on `--reference` cells with parts a quarter of the default's; the row of half the reference's
cells at its parts bounds the reference's own error. Beside them, the same walk of Q and
sigma at the constant P of the contact, on the constant-P default (`fretting.choose_model`) and
on `Varying()`: their energies agree where the two discretisations do.

    python benchmarks/normal_load.py [--repeats 1] [--reference 2048]
"""

import argparse

import numpy as np
from engine_speed import CONTACT, cpu

import fretting as fr
from fretting.models.normal import DEFAULT_CELLS, DEFAULT_LOAD_PART, Varying

CELLS = (64, 128, 256, DEFAULT_CELLS)
PARTS = (16 * DEFAULT_LOAD_PART, 4 * DEFAULT_LOAD_PART, DEFAULT_LOAD_PART)


def walk(P=True):
    """The (P, Q, sigma) walk of the module docstring; its (Q, sigma) at the contact's P when `P` is False."""
    rng = np.random.default_rng(1)
    P0, fP, fp0 = CONTACT.P, CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    Q = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 10)]) * fP
    sigma = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 10)]) * fp0
    loads = np.concatenate([[1.0], rng.uniform(0.7, 1.3, 10)]) * P0
    return fr.History.piecewise_linear(Q, sigma, 16, P=loads if P else None)


def ends(result, history):
    """Outermost stick-zone ends [m] at the vertices, and the half-width [m] of each vertex's contact."""
    rows = history.vertex_step[1:]
    start, end = result.stick_start.values[rows], result.stick_end.values[rows]
    widths = [CONTACT.profile.half_width(P, CONTACT.E_star)[0] for P in history.P[rows]]
    return np.stack([np.nanmin(start, axis=1), np.nanmax(end, axis=1)], axis=1), np.array(widths)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--reference", type=int, default=4 * DEFAULT_CELLS)
    args = parser.parse_args(argv)
    history = walk()
    specs = [Varying(cells) for cells in CELLS]
    specs += [Varying(load_part=part) for part in PARTS if part != DEFAULT_LOAD_PART]
    finest = Varying(args.reference, load_part=DEFAULT_LOAD_PART / 4)
    specs.append(Varying(args.reference // 2, load_part=finest.load_part))
    runs = [cpu(lambda m=spec: fr.simulate(CONTACT, history, model=m), args.repeats) for spec in (*specs, finest)]
    reference = runs[-1][1]
    energy = float(reference.total_dissipation)
    zones, widths = ends(reference, history)
    print(f"varying P: {len(history)} steps; reference {finest.cells} cells, load_part {finest.load_part:.3g}")
    columns = (("cells", 6), ("load_part", 10), ("CPU [s]", 8), ("energy [J/m]", 13), ("energy error", 13))
    print(" ".join(f"{name:>{width}}" for name, width in (*columns, ("stick ends [a]", 15))))
    for spec, (seconds, result) in zip(specs, runs, strict=False):
        now = float(result.total_dissipation)
        found, _ = ends(result, history)
        stick = np.nanmax(np.abs(found - zones) / widths[:, None])
        print(
            f"{spec.cells:>6} {spec.load_part:>10.3g} {seconds:>8.2f} {now:>13.6e} {abs(now - energy) / energy:>13.2e}"
            f" {stick:>15.2e}"
        )
    held = walk(P=False)
    default = fr.choose_model(CONTACT, held)
    print(f"constant P, the same walk of Q and sigma ({len(held)} steps):")
    for label, model in ((f"default ({default.name})", default), (f"Varying({DEFAULT_CELLS})", Varying())):
        seconds, result = cpu(lambda m=model: fr.simulate(CONTACT, held, model=m), args.repeats)
        print(f"  {label:<22} CPU {seconds:6.2f} s   energy {float(result.total_dissipation):.6g} J/m")


if __name__ == "__main__":
    main()
