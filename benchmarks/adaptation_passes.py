"""What the adaptation of the default mesh costs, pass by pass, started warm or cold.

`fretting.adapted_mesh` runs the turning points of the history on a mesh, refines it and runs
them again until nothing is refined. Each pass starts the solver's active set at a turning
point from the slip directions the pass before found there (warm); without that it starts from
the directions of the increment before (cold). On the harness's 10-vertex random scene (Hertz,
8 steps per segment) this prints, for each pass of both, the nodes, the releases after the
first solve per turning point (min to max) and the CPU time of its run, then the CPU time of the
whole default run (fastest of 5), and of gathering the block of 550 of 764 nodes' rows and columns of ``G``
both ways `fretting.models.solver._Factor` could.

With ``--log``, the default's passes instead (`fretting.models.galerkin.adaptation.adapted_model`:
the stage of each, energy, ends or checked, the nodes of its mesh and of the mesh it gives, the
nodes it adds [%], its increments and its CPU time), the CPU time of the adaptation and of the
whole default run and the fallback, on the scenes of the harness that have no closed form, the
non-periodic out-of-phase spectrum of benchmarks/service_life.py (4 and 16 cycles) and the
histories of benchmarks/trajectories.py named (default: one of each kind that adapts differently).

Run:  python benchmarks/adaptation_passes.py [--log [HISTORY ...]]   (about 10 seconds; --log about
two minutes; set OPENBLAS_NUM_THREADS=1). With ``--time [HISTORY ...]``, the CPU time of the
default run of each of those histories (no default ones named), median of 3.
"""

import argparse
import resource
import sys
import timeit

import harness
import numpy as np
import service_life
import trajectories

import fretting as fr

method4 = sys.modules["fretting.models.method4"]
follow_module = sys.modules["fretting.engine.follow"]
adaptation = sys.modules["fretting.models.galerkin.adaptation"]
model_module = sys.modules["fretting.models.galerkin.model"]

#: Histories of benchmarks/trajectories.py logged by default: a walk, an ellipse, a small amplitude
#: (whose energy `_energy_checked` settles) and a rounded flat.
LOGGED = ("walk_s0_8", "ellipse_90", "tiny_1e-4_ellipse", "flat_0.25_walk")


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
        found.append([run.model.x.size, [], cpu()])
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


def logged(contact, history):
    """The default run of `history`: its result, CPU seconds, CPU seconds of the adaptation, and per
    pass of the adaptation (stage, nodes, increments, CPU seconds)."""
    stages, rows, spent = [], [], [0.0]
    follow, stages_of = follow_module._Run.follow, {}

    def tag(stage, function):
        def tagged(*args, **options):
            stages.append(stage)
            try:
                return function(*args, **options)
            finally:
                stages.pop()

        return tagged

    for stage, name in (("energy", "__call__"), ("ends", "_located"), ("checked", "_energy_checked")):
        owner = adaptation._Adaptation if name == "__call__" else adaptation
        stages_of[owner, name] = getattr(owner, name)
        setattr(owner, name, tag(stage, stages_of[owner, name]))

    def timed(run, state):
        if not stages:
            return follow(run, state)
        rows.append([stages[-1], run.model.x.size, len(run.history) - 1, cpu()])
        try:
            return follow(run, state)
        finally:
            rows[-1][3] = cpu() - rows[-1][3]

    adapted = model_module.adapted_model

    def adapting(*args, **options):
        start = cpu()
        try:
            return adapted(*args, **options)
        finally:
            spent[0] = cpu() - start

    follow_module._Run.follow, model_module.adapted_model = timed, adapting
    try:
        start = cpu()
        result = fr.simulate(contact, history)
        return result, cpu() - start, spent[0], rows
    finally:
        follow_module._Run.follow, model_module.adapted_model = follow, adapted
        for (owner, name), function in stages_of.items():
            setattr(owner, name, function)


def logged_histories(names):
    """``name: (contact, history)`` of the scenes without a closed form, the spectra and the
    histories `names` of benchmarks/trajectories.py."""
    histories = {scene.name: (scene.contact, scene.history) for scene in harness.scenes() if not scene.closed_form}
    for cycles in (4, 16):
        path = f"{harness.HERE}/.cache/out_of_phase_{cycles}.toml"
        harness.HERE.joinpath(".cache").mkdir(exist_ok=True)
        with open(path, "w") as file:
            file.write(service_life.history_text(cycles, True, "out_of_phase"))
        histories[f"out_of_phase_spectrum_{cycles}"] = fr.read_history(path)
    cases = trajectories.cases()
    return histories | {name: cases[name] for name in names}


def log(names):
    """Print the default's passes (`logged`) on the `logged_histories`."""
    for name, (contact, history) in logged_histories(names).items():
        result, seconds, adapting, rows = logged(contact, history)
        print(f"{name}: {seconds:.2f} s CPU, adaptation {adapting:.2f} s, {result.attrs['nodes']} nodes")
        print(f"  fallback: {result.attrs.get('model_fallback')}")
        for k, (stage, nodes, increments, spent) in enumerate(rows):
            after = rows[k + 1][1] if k + 1 < len(rows) else int(result.attrs["nodes"])
            print(
                f"  {stage:8} {nodes:5d} -> {after:5d} nodes (+{100 * (after - nodes) / nodes:6.2f} %)"
                f"  {increments:4d} increments  {spent:6.2f} s"
            )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--log", nargs="*", metavar="HISTORY", help="the default's passes (module docstring)")
    parser.add_argument("--time", nargs="*", metavar="HISTORY", help="CPU time of the default, median of 3")
    args = parser.parse_args()
    if args.log is not None:
        log(args.log or LOGGED)
        return
    if args.time is not None:
        for name, (contact, history) in logged_histories(args.time).items():
            seconds = [whole(contact, history) for _ in range(3)]
            print(f"{name}: {np.median(seconds):.2f} s CPU (median of {', '.join(f'{s:.2f}' for s in seconds)})")
        return
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
