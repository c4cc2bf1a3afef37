"""What the adaptation of the default mesh costs, pass by pass, started warm or cold.

`fretting.adapted_mesh` runs the turning points of the history on a mesh, refines it and runs
them again until nothing is refined. Each pass starts the solver's active set at a turning
point from the slip directions the pass before found there (warm); without that it starts from
the directions of the increment before (cold). On the harness's 10-vertex random scene (Hertz,
8 steps per segment) this prints, for each pass of both, the nodes, the releases after the
first solve per turning point (min to max) and the CPU time of its run, then the CPU time of the
whole default run (fastest of 5), and of gathering the block of 550 of 764 nodes' rows and columns of ``G``
both ways `fretting.models.solver._Factor` could.

Run:  python benchmarks/adaptation_passes.py   (about 10 seconds; set OPENBLAS_NUM_THREADS=1)
"""

import resource
import sys
import timeit

import harness
import numpy as np

import fretting as fr

method4 = sys.modules["fretting.models.method4"]
follow_module = sys.modules["fretting.engine.follow"]
adaptation = sys.modules["fretting.models.galerkin.adaptation"]


def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def passes(contact, history):
    """(nodes, releases of each turning point, CPU seconds) of each pass of the adaptation."""
    found, solve, follow = [], method4.solve_increment, follow_module._Run.follow

    def counting(*args):
        increment = solve(*args)
        found[-1][1].append(increment.iterations)
        return increment

    def timed(run, state):
        found.append([run.scene.x.size, [], cpu()])
        end = follow(run, state)
        found[-1][2] = cpu() - found[-1][2]
        return end

    method4.solve_increment, follow_module._Run.follow = counting, timed
    try:
        fr.adapted_mesh(contact, history)
    finally:
        method4.solve_increment, follow_module._Run.follow = solve, follow
    return found


def whole(contact, history):
    """CPU seconds of one default run."""
    start = cpu()
    fr.simulate(contact, history)
    return cpu() - start


def main():
    contact = harness.hertz_contact()
    history = harness.baseline_history(contact, 8)
    warm_start = adaptation._interpolated_directions
    for label, directions in (("warm", warm_start), ("cold", lambda *args: None)):
        adaptation._interpolated_directions = directions
        passes(contact, history)  # once to load and compile
        print(f"{label}: nodes, releases per turning point, CPU s of the pass")
        for nodes, releases, seconds in passes(contact, history):
            print(f"  {nodes:5d}   {min(releases)} to {max(releases)}   {seconds:.3f}")
        print(f"  whole default run: {min(whole(contact, history) for _ in range(5)):.3f} s CPU (fastest of 5)")
    adaptation._interpolated_directions = warm_start
    G = np.random.default_rng(0).random((764, 764))
    nodes = np.sort(np.random.default_rng(1).choice(764, 550, replace=False))
    for label, gather in (
        ("np.ix_", lambda: G[np.ix_(nodes, nodes)]),
        ("rows then columns", lambda: G[nodes][:, nodes]),
    ):
        print(f"gather {label}: {min(timeit.repeat(gather, number=20, repeat=5)) / 20 * 1e3:.2f} ms")


if __name__ == "__main__":
    main()
