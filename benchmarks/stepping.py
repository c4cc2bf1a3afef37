"""Stepping a history one increment at a time from Python against `fretting.simulate` over it.

For each model (the 384-node grid, an adapted Galerkin mesh, the exact model of Q alone) the
history is run by `simulate` and by a loop of `Stepper.step` calls with the same model; the
script prints the CPU time of each (best of `--repeats`), their ratio, and whether the slip and
energy of every step are equal bit for bit. The engine runs BLAS on one thread either way. A last
line steps the exact model again with every branch of the history already solved (its model built
and stepped once): what stepping costs beside evaluating the closed form one branch at a time,
where `simulate` evaluates the branches of many steps at once (`ExactModel.prepare`).

    python benchmarks/stepping.py [--repeats 3]
"""

import argparse

import numpy as np
from engine_speed import CONTACT, cpu, walks

import fretting as fr


def histories():
    """(label, history, model) of the scenes: random Q and sigma walks, and Q alone."""
    walk, shear = walks()
    mesh = fr.models.Mesh(theta=fr.adapted_mesh(CONTACT, walk))
    return [
        ("Q and sigma, grid 384", walk, fr.models.Grid(384)),
        (f"Q and sigma, mesh of {mesh.theta.size} nodes", walk, mesh),
        ("Q alone, exact model", shear, fr.choose_model(CONTACT, shear)),
    ]


def stepped(history, model):
    """Slip [m] and energy [J/m] after every step, stepped one increment at a time."""
    stepper = fr.Stepper(CONTACT, model)
    slip, energy = [], []
    for Q, sigma in zip(history.Q, history.sigma, strict=True):
        stepper.step(Q, sigma)
        slip.append(stepper.state.slip)
        energy.append(stepper.state.dissipated)
    return np.array(slip), np.array(energy)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"{'scene':<34} {'steps':>6} {'simulate [s]':>13} {'stepped [s]':>12} {'ratio':>6}  bit for bit")
    for label, history, model in histories():
        whole_time, whole = cpu(lambda h=history, m=model: fr.simulate(CONTACT, h, model=m), args.repeats)
        step_time, (slip, _) = cpu(lambda h=history, m=model: stepped(h, m), args.repeats)
        same = np.array_equal(slip[1:], whole.slip.values[1:])
        row(label, len(history), whole_time, step_time, same)
    built = model.build(CONTACT)  # the last scene's: the exact model
    stepped(history, built)  # every branch of the history solved and cached
    cached_time, (slip, _) = cpu(lambda: stepped(history, built), args.repeats)
    same = np.array_equal(slip[1:], whole.slip.values[1:])
    row("  the same, branches solved before", len(history), whole_time, cached_time, same)


def row(label, steps, whole_time, step_time, same):
    """Print one scene's line of the table."""
    ratio = step_time / whole_time
    print(f"{label:<34} {steps:>6} {whole_time:>13.3f} {step_time:>12.3f} {ratio:>6.2f}  {same}")


if __name__ == "__main__":
    main()
