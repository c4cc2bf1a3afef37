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

With ``--drivers``, what sets the node count of the adapted mesh (`fretting.adapted_mesh`, both
stages) on the same histories: its nodes as it is, and with each error indicator of
`fretting.models.galerkin.element_targets` left out in turn (`DRIVERS`): the stick ends (the
spans of the elements in slip zones and at boundaries, ``swept`` and ``end``), the energy (zone
and boundary fractions), the slip (the grading from the contact's edges), the traction (the
elements at the pressure's breakpoints).

With ``--ends [HISTORY ...]`` (default: `trajectories.QUICK`), the stick ends that `located_end`
places at every step on the mesh of the energy stage alone (every span `ENERGY_SPAN`: the ends
located without refining for them) and on the default's mesh, against the converged reference
of benchmarks/trajectories.py (its cache): nodes, the worst distance [a] and the steps over
1e-3 a and 5e-4 a, and the worst slip relative to the step's (``slip_step``), which that
refinement holds.

Run:  python benchmarks/adaptation_passes.py [--log [HISTORY ...]] [--drivers [HISTORY ...]]
[--ends [HISTORY ...]] (about 10 seconds; --log about two minutes, --drivers about five, --ends
one plus the references not yet cached; set OPENBLAS_NUM_THREADS=1).
With ``--time [HISTORY ...]``, the CPU time of the default run of each of those histories (no
default ones named), median of 3.
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
from fretting.analysis.accuracy import zone_distance

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


mesh_module = sys.modules["fretting.models.galerkin.mesh"]
SPAN, ZONE_FRACTION = mesh_module._span, mesh_module.zone_fraction
GRADED_FROM_EDGE, ELEMENT_TARGETS = mesh_module._graded_from_edge, adaptation.element_targets


def _without_ends(position, rtol, span=None):
    """`mesh._span` with no bound from the spans asked for the stick ends (``swept``, ``end``)."""
    return SPAN(position, rtol) if span is None else np.full(np.shape(position), np.inf)


def _slip_grading(theta, left, rtol):
    """`mesh._graded_from_edge` with the `zone_fraction` it grades by, while that is left out."""
    with _patched({(mesh_module, "zone_fraction"): ZONE_FRACTION}):
        return GRADED_FROM_EDGE(theta, left, rtol)


def _without_breakpoints(theta, ds, rtol=mesh_module.DEFAULT_RTOL, breakpoints=(), *rest, **options):
    """`element_targets` as the adaptation calls it, without the pressure's breakpoints."""
    return ELEMENT_TARGETS(theta, ds, rtol, (), *rest, **options)


#: The error indicators of `element_targets` that `--drivers` leaves out, each by the functions
#: it replaces: ``(module, name): replacement``.
DRIVERS = {
    "ends": {(mesh_module, "_span"): _without_ends},
    "energy": {
        (mesh_module, "zone_fraction"): lambda rtol: np.inf,
        (mesh_module, "boundary_fraction"): lambda rtol: np.inf,
        (mesh_module, "_graded_from_edge"): _slip_grading,
    },
    "slip": {(mesh_module, "_graded_from_edge"): lambda theta, left, rtol: np.full(theta.size - 1, np.inf)},
    "traction": {(adaptation, "element_targets"): _without_breakpoints},
}


class _patched:
    """Replace functions ``(module, name): replacement`` for a ``with`` block."""

    def __init__(self, functions):
        self.functions, self.saved = functions, {}

    def __enter__(self):
        for (module, name), function in self.functions.items():
            self.saved[module, name] = getattr(module, name)
            setattr(module, name, function)

    def __exit__(self, *exc):
        for (module, name), function in self.saved.items():
            setattr(module, name, function)


def drivers(names):
    """Print the nodes of the adapted mesh, and with each indicator of `DRIVERS` left out."""
    for name, (contact, history) in logged_histories(names).items():
        nodes = {"all": fr.adapted_mesh(contact, history).size}
        for driver, functions in DRIVERS.items():
            with _patched(functions):
                nodes[driver] = fr.adapted_mesh(contact, history).size
        shares = [f"{d} {n:5d} ({100 * (n / nodes['all'] - 1):+4.0f} %)" for d, n in nodes.items() if d != "all"]
        print(f"{name:30} {nodes['all']:5d} nodes; without " + ", ".join(shares), flush=True)


def _energy_spans(steps, recorded):
    """`adaptation._spans` with every span `ENERGY_SPAN` and the grading `ENERGY_GRADING`: no refinement for the
    stick ends."""
    return np.tile([mesh_module.ENERGY_SPAN, mesh_module.ENERGY_SPAN, mesh_module.ENERGY_GRADING], (steps.size, 1))


def ends(names):
    """Print the located stick ends at every step on the energy's mesh and on the default's, against
    the reference of benchmarks/trajectories.py."""
    cases = trajectories.cases()
    for name in names or trajectories.QUICK:
        contact, history = cases[name]
        reference = trajectories.fine_run(
            contact, history, trajectories.REFERENCE_ELEMENTS, trajectories.BANDED.get(name, 0)
        )
        reference = trajectories.with_located_ends(reference, contact)
        for label, functions in (("energy mesh", {(adaptation, "_spans"): _energy_spans}), ("default", {})):
            with _patched(functions):
                result = fr.simulate(contact, history)
            run = trajectories.fields_of(result)
            distance = np.array([_zone_distance(run, reference, k) / contact.a for k in range(1, len(history))])
            slip_step = trajectories.score(run, reference, contact, history)["slip_step"][0]
            print(
                f"{name:28} {label:11} {result.attrs['nodes']:5d} nodes  ends: worst {distance.max():.1e} a "
                f"(step {1 + distance.argmax()}), over 1e-3 a at {np.sum(distance > 1e-3)} and over 5e-4 a at "
                f"{np.sum(distance > 5e-4)} of {distance.size} steps;  slip_step {slip_step:.1e}",
                flush=True,
            )


def _zone_distance(run, reference, k):
    """`zone_distance` [m] of the stick zones of step `k` of `run` and `reference` (trajectories' fields)."""
    zones = (trajectories._zones(fields["stick_start"][k], fields["stick_end"][k]) for fields in (run, reference))
    return zone_distance(*zones)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--log", nargs="*", metavar="HISTORY", help="the default's passes (module docstring)")
    parser.add_argument("--time", nargs="*", metavar="HISTORY", help="CPU time of the default, median of 3")
    parser.add_argument("--drivers", nargs="*", metavar="HISTORY", help="what sets the nodes (module docstring)")
    parser.add_argument("--ends", nargs="*", metavar="HISTORY", help="located ends at every step (module docstring)")
    args = parser.parse_args()
    if args.ends is not None:
        ends(args.ends)
        return
    if args.drivers is not None:
        drivers(args.drivers or LOGGED)
        return
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
