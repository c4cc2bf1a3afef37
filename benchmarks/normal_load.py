"""Convergence and speed of the model of a varying normal load (`fretting.models.Varying`).

A random walk of (P, Q, sigma) on the Hertz scene of benchmarks/engine_speed.py (P between 0.7
and 1.3 of the contact's, Q within 0.4 f P0, sigma within 0.4 f p0, independent draws, 16 steps
per segment; `--walk test`: the scene and walk of tests/models/test_normal_load.py, f = 0.5, four segments).

Speed against error: the walk on 64 to `DEFAULT_CELLS` cells at the default ``load_part``, then
on the default cells with other parts. For each the CPU time (best of `--repeats`), the total
energy, its relative error and the largest error of the stick-zone ends at every step (in the
half-width of the step's contact), both against a run on `--reference` cells with parts a quarter
of the default's. Then 512 cells and the default with the cells shifted: the largest contact's interval ``A``
widened by 0.1 to 0.5 percent, which moves the cells by up to a cell against the contact edges
and the stick zones (the error of the energy changes with it, not with the parts).

The reference converged: the same walk at the reference's parts on the default's cells, doubled up to the
reference, each row with the change of the energy and of the stick ends from the row before; the
changes fall with the cells, so the reference's own error is below the last change.

Beside them, the same walk of Q and sigma at the constant P of the contact, on the constant-P
default (`fretting.choose_model`) and on `Varying()`.

    python benchmarks/normal_load.py [--repeats 1] [--reference 2048] [--walk bench|test]
"""

import argparse

import numpy as np
from engine_speed import CONTACT, cpu

import fretting as fr
from fretting.models.normal import DEFAULT_CELLS, DEFAULT_LOAD_PART, Varying

CELLS = (64, 128, 256, 512, DEFAULT_CELLS)
PARTS = (16 * DEFAULT_LOAD_PART, 4 * DEFAULT_LOAD_PART, DEFAULT_LOAD_PART, DEFAULT_LOAD_PART / 4)
#: contact, seed, segments
SHIFTS = (1.001, 1.002, 1.003, 1.004, 1.005)  # A over the largest contact's half-width
#: Cells run with the shifts: 512, where some positions of the cells miss 1e-4 of the energy, and the default
SHIFTED_CELLS = (512, DEFAULT_CELLS)
WALKS = {"bench": (CONTACT, 1, 10), "test": (fr.Contact(fr.Hertz(0.05), 115e9, 0.5, 1e5), 3, 4)}


def walk(name, P=True):
    """The contact and the (P, Q, sigma) walk `name` of the module docstring (at the contact's P when `P` is False)."""
    contact, seed, segments = WALKS[name]
    rng = np.random.default_rng(seed)
    P0, fP, fp0 = contact.P, contact.f * contact.P, contact.f * contact.p0
    loads = np.concatenate([[1.0], rng.uniform(0.7, 1.3, segments)]) * P0
    Q = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, segments)]) * fP
    sigma = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, segments)]) * fp0
    return contact, fr.History.piecewise_linear(Q, sigma, 16, P=loads if P else None)


def stick_error(result, reference):
    """Largest difference [a] of the stick-zone ends at any step, and whether the zones found differ in number."""
    worst, differ = 0.0, False
    for name in ("stick_start", "stick_end"):
        found, expected = result[name].values, reference[name].values
        width = max(found.shape[1], expected.shape[1])
        found, expected = (
            np.pad(v, ((0, 0), (0, width - v.shape[1])), constant_values=np.nan) for v in (found, expected)
        )
        differ |= bool(np.any(np.isnan(found) != np.isnan(expected)))
        error = np.abs(found - expected) / result.a.values[:, None]
        worst = max(worst, float(np.nanmax(error, initial=0.0)))
    return worst, differ


def row(spec, seconds, result, reference, label=None):
    """One line of a table: `label` (default: the spec's cells), the spec's parts, its CPU time and energy,
    and its differences from `reference`."""
    energy, expected = float(result.total_dissipation), float(reference.total_dissipation)
    stick, differ = stick_error(result, reference)
    flag = " (zones differ)" if differ else ""
    return (
        f"{spec.cells if label is None else label:>6} {spec.load_part:>10.3g} {seconds:>8.2f} {energy:>13.6e}"
        f" {(energy - expected) / expected:>+13.2e} {stick:>12.2e}{flag}"
    )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--reference", type=int, default=4 * DEFAULT_CELLS, help="cells: the default's times 2^k")
    parser.add_argument("--walk", choices=sorted(WALKS), default="bench")
    args = parser.parse_args(argv)
    contact, history = walk(args.walk)
    finest = DEFAULT_LOAD_PART / 4
    refined = [DEFAULT_CELLS]
    while refined[-1] < args.reference:
        refined.append(2 * refined[-1])
    table = [(cells, DEFAULT_LOAD_PART) for cells in CELLS] + [(DEFAULT_CELLS, part) for part in PARTS]
    table = list(dict.fromkeys(table))
    runs = {}
    for cells, part in list(dict.fromkeys(table + [(cells, finest) for cells in refined])):
        spec = Varying(cells, load_part=part)
        repeats = args.repeats if (cells, part) in table else 1
        runs[cells, part] = spec, *cpu(lambda m=spec: fr.simulate(contact, history, model=m), repeats)
    reference = runs[args.reference, finest][2]
    header = (
        f"{'cells':>6} {'load_part':>10} {'CPU [s]':>8} {'energy [J/m]':>13} {'energy error':>13} {'stick ends':>12}"
    )
    print(f"varying P, walk {args.walk!r}: {len(history)} steps")
    print(f"errors against {args.reference} cells at load_part {finest:.3g}: the energy's relative, signed;")
    print("the stick ends' largest at any step [a]")
    print(header)
    for key in table:
        print(row(*runs[key], reference))
    A = Varying().resolved_for(contact, history).half_width
    for cells in SHIFTED_CELLS:
        print(f"{cells} cells at load_part {DEFAULT_LOAD_PART:.3g} over A widened by the factor")
        for shift in SHIFTS:
            spec = Varying(cells, half_width=shift * A)
            seconds, result = cpu(lambda m=spec: fr.simulate(contact, history, model=m), args.repeats)
            print(row(spec, seconds, result, reference, label=shift))
    print(f"the reference converged: cells doubled at load_part {finest:.3g}, each row against the row before")
    print(header.replace("error", "change"))
    for coarse, fine in zip(refined, refined[1:], strict=False):
        print(row(*runs[fine, finest], runs[coarse, finest][2]))
    _, held = walk(args.walk, P=False)
    default = fr.choose_model(contact, held)
    print(f"constant P, the same walk of Q and sigma ({len(held)} steps):")
    for label, model in ((f"default ({default.name})", default), (f"Varying({DEFAULT_CELLS})", Varying())):
        seconds, result = cpu(lambda m=model: fr.simulate(contact, held, model=m), args.repeats)
        print(f"  {label:<22} CPU {seconds:6.2f} s   energy {float(result.total_dissipation):.6g} J/m")


if __name__ == "__main__":
    main()
