"""Linear solves and fresh Cholesky factorisations per increment of the active-set solver (issue 34).

Run:  python benchmarks/solver_profile.py [--quick] [--scenes NAME ...] [--trajectories]

Runs the default (``fretting.simulate(contact, history)``) on the scenes of `speed_ratio` (full
length; --quick, its short ones; --trajectories, the histories of ``trajectories.py --quick``
instead) and counts, over every increment that `fretting.models.solver`
solves (the mesh adaptation's passes included): the solves of the slipping block, the fresh
factorisations of it (a bordering of an empty factor), the solves taken through the stuck nodes
(`fretting.models.solver.Stiffness.solve_slipping`), and the CPU time (one BLAS thread) spent in
``solve_increment`` against the whole run's. Against another checkout:
``PYTHONPATH=<checkout> python benchmarks/solver_profile.py``.
"""

import argparse
import os
import time

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import speed_ratio  # noqa: E402
import trajectories  # noqa: E402

import fretting as fr  # noqa: E402
from fretting.models import method4, normal, solver  # noqa: E402


class Counts:
    """The solver's calls during one run, counted by wrapping its functions in place."""

    def __init__(self):
        self.increments = self.solves = self.fresh = self.complement = 0
        self.cpu = 0.0

    def __enter__(self):
        self.saved = (solver.solve_increment, solver._Factor.solve, solver._Factor._border)
        increment, solve, border = self.saved

        def counted_increment(*args, **kwargs):
            began = time.process_time()
            try:
                return increment(*args, **kwargs)
            finally:
                self.cpu += time.process_time() - began
                self.increments += 1

        def counted_solve(factor, slipping, rhs):
            self.solves += 1
            self.complement += factor.stiffness.by_complement(slipping)
            return solve(factor, slipping, rhs)

        def counted_border(factor, new):
            self.fresh += factor.order.size == 0
            return border(factor, new)

        method4.solve_increment = normal.solve_increment = counted_increment
        solver._Factor.solve, solver._Factor._border = counted_solve, counted_border
        return self

    def __exit__(self, *exc):
        method4.solve_increment = normal.solve_increment = self.saved[0]
        solver._Factor.solve, solver._Factor._border = self.saved[1:]


def profile(contact, history):
    """The `Counts` of the default's run of `history`, with its nodes and whole CPU time [s]."""
    with Counts() as counts:
        began = time.process_time()
        result = fr.simulate(contact, history)
        whole = time.process_time() - began
    return counts, result.sizes["x"], whole


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the short scenes of speed_ratio --quick")
    parser.add_argument("--scenes", nargs="+", default=None, help="these scenes only (default: all)")
    parser.add_argument("--trajectories", action="store_true", help="the histories of trajectories.py --quick")
    args = parser.parse_args(argv)
    if args.trajectories:
        cases = {name: trajectories.cases()[name] for name in trajectories.QUICK}
    else:
        cases = {scene.name: (scene.contact, scene.history) for scene in speed_ratio.scenes(args.quick)}
    print(f"fretting from {fr.__file__}")
    header = "history             nodes  increments  solves/inc  fresh/inc  complement/inc  solver ms/inc"
    print(header + "  solver s  run s")
    total = 0.0
    for name, (contact, history) in cases.items():
        if args.scenes and name not in args.scenes:
            continue
        c, nodes, whole = profile(contact, history)
        n, total = max(c.increments, 1), total + whole
        print(
            f"{name:19s} {nodes:5d}  {c.increments:10d}  {c.solves / n:10.2f}  {c.fresh / n:9.2f}  "
            f"{c.complement / n:14.2f}  {1e3 * c.cpu / n:13.2f}  {c.cpu:8.2f}  {whole:5.2f}"
        )
    print(f"run s in all: {total:.1f}")


if __name__ == "__main__":
    main()
