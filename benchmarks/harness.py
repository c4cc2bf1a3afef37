"""The speed-against-error benchmark: scenes, engine configurations, a hand-written baseline, timing.

benchmarks/speed_vs_error.py runs it and writes the report; the other scripts of benchmarks/ take
their scenes from here (``import harness``: run them as ``python benchmarks/<script>.py``, which
puts this folder on the path). Not part of the installed package.

Scenes: a Hertz contact under Q cycling (reference: Cattaneo-Mindlin with the Masing rule, the
energy per cycle of Mindlin-Deresiewicz), under in-phase Q and sigma (Nowell-Hills with the
Masing rule), a rounded flat punch under a seeded random Q/sigma path and a Hertz contact under
90-degree out-of-phase Q/sigma (both: the most resolved run, `reference_configuration`), and the
10-vertex random Q/sigma Hertz path on which `baseline_simulate`, the dense active-set method-4
solver the field writes by hand, is timed beside the engine. Errors are those of
`fretting.analysis.accuracy.score`, each the largest over the steps (or cycles) of a run.

Only the public interface is used: ``fretting.simulate(contact, history, **kwargs)`` and its
dataset, so any model the engine offers is measured the same way.

Also here, the one support module that the scripts and the tests share (the tests find it through
pytest's ``pythonpath``): their scenes (`hertz_contact`, `hard_rounded_flat`, `asymmetric_flat`,
the profile families of the property tests `SHAPES`, `family_contact`), the Galerkin mesh's
adaptive loop written out by hand (`adapt`) and the band of the in-phase comparison (`END_BAND`).
"""

import functools
import itertools
import json
import math
import os
import platform
import resource
import subprocess
import sys
import time
import tracemalloc
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import dense_method4
import numpy as np
import xarray as xr

import fretting as fr
from fretting.analysis import accuracy
from fretting.models import galerkin as gk
from fretting.models.method4 import stick_zones
from fretting.models.solver import solve_increment

#: This folder: the long runs' child processes import the harness from it.
HERE = Path(__file__).resolve().parent

#: The engine as a user gets it: ``fretting.simulate(contact, history)``.
DEFAULT = ("default", {})

#: Errors within this factor count as equal when the baseline is matched to the default.
EQUAL = 1 + 1e-6

#: Environment that limits BLAS and OpenMP to one thread.
ONE_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}

#: Names of the long targets that `benchmark` runs (None: all of `long_targets`).
LONG_RUNS = None

ERRORS = ("stick_ends_a", "energy_rel", "traction_fp0")

#: Steps after which the slip error is also held relative to the step's own largest slip (before it
#: only relative to the history's largest): the first increments of a history slip in slivers at the
#: contact edges, whose largest slip is a tiny part of what follows.
FIRST_STEPS = 4


# -- Configurations -------------------------------------------------------------------------


def configurations(quick=False):
    """Engine configurations to measure, coarse to fine within each model.

    The one place that lists them: add the engine's other models here.

    Parameters
    ----------
    quick : bool
        A few cheap ones, for a smoke test.

    Returns
    -------
    list of (str, dict)
        Label and keyword arguments of `fretting.simulate`.
    """
    nodes = (32, 64) if quick else (64, 128, 256, 384, 512, 768, 1024)
    tolerances = () if quick else (1e-3, 1e-4)
    return [(f"chebyshev N={n}", {"nodes": n}) for n in nodes] + [
        (f"galerkin rtol={r:g}", {"rtol": r}) for r in tolerances
    ]


def reference_configuration(quick=False, baseline=False):
    """The most resolved configuration: the reference of scenes without a closed form, ``(label, kwargs)``.

    The Gauss-Chebyshev grid of 1536 nodes, 1.5 times the finest of `configurations`; on the
    `baseline` scene twice the finest of `baseline_configurations` (3072), which must reach
    the default's errors there for the ratio at equal error to be measured, and the reference
    must be finer still (a run scored against itself has no error).
    """
    if baseline:
        nodes = 2 * max(n for _, n in baseline_configurations(quick))
    else:
        nodes = 256 if quick else 1536
    return (f"chebyshev N={nodes}", {"nodes": nodes})


def baseline_configurations(quick=False):
    """Node counts of the hand-written baseline, ``(label, nodes)`` pairs."""
    nodes = (32, 64) if quick else (64, 128, 256, 384, 512, 768, 1024, 1536)
    return [(f"baseline N={n}", n) for n in nodes]


def _model(kwargs):
    return kwargs.get("model", "chebyshev")


# -- Scenes ---------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Scene:
    """A contact and a load history to measure on.

    Attributes
    ----------
    name, title : str
        Short name (CSV, file names) and one-line description.
    contact : fretting.Contact
    history : fretting.History
        Every history has cycles: the energy error is per cycle.
    closed_form : bool
        Reference from the Masing rule over Cattaneo-Mindlin / Nowell-Hills (proportional loads
        on a Hertz contact); otherwise the run of `reference_configuration`.
    baseline : bool
        The baseline solver runs on this scene too.
    """

    name: str
    title: str
    contact: fr.Contact
    history: fr.History
    closed_form: bool
    baseline: bool = False


@dataclass(frozen=True, eq=False)
class LongTarget:
    """A long constant-amplitude sinusoidal history with its targets, run at default settings.

    Attributes
    ----------
    seconds : float
        Wall time allowed [s], one core.
    energy : float or None
        Largest ``|W / W_ref - 1|`` allowed over all cycles.
    memory : float or None
        Peak resident memory allowed [bytes].
    scene : str or None
        Scene whose reference gives the energies of the first cycles (the same loads); None:
        the Masing closed form.
    """

    name: str
    title: str
    contact: fr.Contact
    Q_amplitude: float
    sigma_amplitude: float
    phase_deg: float
    cycles: int
    steps_per_cycle: int
    ramp_steps: int
    seconds: float
    energy: float | None = None
    memory: float | None = None
    scene: str | None = None

    def history(self, cycles=None):
        """The first `cycles` cycles (all by default)."""
        return fr.History.sinusoidal(
            self.Q_amplitude,
            self.sigma_amplitude,
            self.phase_deg,
            cycles=self.cycles if cycles is None else cycles,
            steps_per_cycle=self.steps_per_cycle,
            ramp_steps=self.ramp_steps,
        )


def hertz_contact():
    """R = 50 mm, E = 210 GPa, nu = 0.3, f = 0.6, P = 100 N/mm (a = 0.235 mm, p0 = 271 MPa)."""
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


def hard_rounded_flat():
    """Flat of half-width 1 mm, corners of radius 20 mm, E_star = 115 GPa, f = 0.5, P = 300 N/mm: a = 1.14 b."""
    return fr.Contact(fr.RoundedFlat(b=1e-3, R=0.02), 115e9, 0.5, 3e5)


#: Band [a] around the stick ends of a history outside which the exact in-phase model and method 4
#: on a fine mesh are compared (tests/models/test_inphase.py, benchmarks/inphase_accuracy.py).
END_BAND = 0.01


def rounded_flat_contact():
    """Flat of half-width 0.2 mm with 50 mm corners, otherwise as `hertz_contact` (a = 0.386 mm)."""
    return fr.Contact(fr.RoundedFlat(2e-4, 0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


def random_cycles(contact, cycles, steps_per_segment, seed):
    """Seeded random cycles: Q up to a peak, then down to a valley, sigma to independent values.

    ``|Q| / (f P)`` is uniform in [0.3, 0.7) at each turn, alternately positive and negative;
    ``sigma / (f p0)`` uniform in [-0.5, 0.5), from ``numpy.random.default_rng(seed)``.
    """
    rng = np.random.default_rng(seed)
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    Q = np.concatenate([[0.0], rng.uniform(0.3, 0.7, 2 * cycles) * np.tile([1.0, -1.0], cycles) * fP])
    sigma = np.concatenate([[0.0], rng.uniform(-0.5, 0.5, 2 * cycles) * fp0])
    path = fr.History.piecewise_linear(Q, sigma, steps_per_segment)
    cycle = np.concatenate([[0], np.repeat(np.arange(1, cycles + 1), 2 * steps_per_segment)])
    return fr.History(path.Q, path.sigma, path.vertex_step, cycle)


def baseline_history(contact, steps_per_segment=8, seed=0):
    """10 random vertices, ``Q/(f P)`` uniform in [-0.8, 0.8), ``sigma/(f p0)`` in [-1, 1), from zero; one cycle.

    The cost history of benchmarks/accuracy_vs_nodes.py.
    """
    rng = np.random.default_rng(seed)
    Q = rng.uniform(-0.8, 0.8, 10) * contact.f * contact.P
    sigma = rng.uniform(-1.0, 1.0, 10) * contact.f * contact.p0
    Q[0] = sigma[0] = 0.0
    return fr.History.piecewise_linear(Q, sigma, steps_per_segment).as_cycle()


def long_targets(quick=False):
    """The long-run targets of issue 5 (shortened in quick mode; the time limits stay)."""
    hertz = hertz_contact()
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q_cycles, cycles, steps, ramp = (40, 10, 8, 4) if quick else (100_000, 2000, 128, 16)
    common = {"contact": hertz, "ramp_steps": ramp, "seconds": 10.0}
    return [
        LongTarget(
            "hertz_Q_long",
            "Hertz, Q = 0.6 fP sin, 64 steps per cycle",
            Q_amplitude=0.6 * fP,
            sigma_amplitude=0.0,
            phase_deg=0.0,
            cycles=Q_cycles,
            steps_per_cycle=8 if quick else 64,
            energy=1e-4,
            memory=2e9,
            **common,
        ),
        LongTarget(
            "in_phase_long",
            "Hertz, Q = 0.6 fP sin, sigma = 0.6 f p0 sin",
            Q_amplitude=0.6 * fP,
            sigma_amplitude=0.6 * fp0,
            phase_deg=0.0,
            cycles=cycles,
            steps_per_cycle=steps,
            **common,
        ),
        LongTarget(
            "out_of_phase_long",
            "Hertz, Q = 0.5 fP sin, sigma = 0.8 f p0 sin(+90 deg)",
            Q_amplitude=0.5 * fP,
            sigma_amplitude=0.8 * fp0,
            phase_deg=90.0,
            cycles=cycles,
            steps_per_cycle=steps,
            scene="hertz_out_of_phase",
            **common,
        ),
    ]


def scenes(quick=False):
    """The scenes of the benchmark, smaller in quick mode."""
    hertz, flat = hertz_contact(), rounded_flat_contact()
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    cycles, per_cycle, per_segment = (2, 8, 2) if quick else (3, 64, 16)
    out_of_phase = next(t for t in long_targets(quick) if t.name == "out_of_phase_long")
    sine = fr.History.sinusoidal
    return [
        Scene(
            "hertz_Q",
            f"Hertz, Q = 0.6 fP sin, {cycles} cycles of {per_cycle} steps",
            hertz,
            sine(0.6 * fP, cycles=cycles, steps_per_cycle=per_cycle),
            closed_form=True,
        ),
        Scene(
            "hertz_in_phase",
            f"Hertz, Q = 0.6 fP sin, sigma = 0.6 f p0 sin, {cycles} cycles of {per_cycle} steps",
            hertz,
            sine(0.6 * fP, 0.6 * fp0, cycles=cycles, steps_per_cycle=per_cycle),
            closed_form=True,
        ),
        Scene(
            "rounded_flat_random",
            f"rounded flat (b/a = 0.52), {2 * cycles} seeded random Q/sigma cycles of 2 x {per_segment} steps",
            flat,
            random_cycles(flat, 2 * cycles, per_segment, seed=5),
            closed_form=False,
        ),
        Scene(
            "hertz_out_of_phase",
            f"Hertz, Q = 0.5 fP sin, sigma = 0.8 f p0 sin(+90 deg), 3 cycles of {out_of_phase.steps_per_cycle} steps",
            hertz,
            out_of_phase.history(3),
            closed_form=False,
        ),
        Scene(
            "baseline_random",
            f"Hertz, 10 random Q/sigma vertices, {2 if quick else 8} steps per segment (the baseline's scene)",
            hertz,
            baseline_history(hertz, 2 if quick else 8),
            closed_form=False,
            baseline=True,
        ),
    ]


# -- Profile families: random contacts of the property tests and of default_out_of_phase.py ------


def asymmetric_flat(b=5e-4, right=0.01, left=0.04):
    """Flat of half-width `b` [m] with a corner of radius `right` [m] at x > b and `left` [m] at x < -b.

    Returns ``h0``, its slope and the ends of the flat, where the curvature jumps.
    """

    def h0(x):
        x = np.asarray(x, float)
        return np.where(x > b, (x - b) ** 2 / (2 * right), np.where(x < -b, (x + b) ** 2 / (2 * left), 0.0))

    def slope(x):
        x = np.asarray(x, float)
        return np.where(x > b, (x - b) / right, np.where(x < -b, (x + b) / left, 0.0))

    return h0, slope, (-b, b)


E_STAR = 115e9


@functools.cache
def family_contact(kind, shape, f, P):
    """A contact of one of the families of `SHAPES` (``E_star = E_STAR``); `shape`: lengths [m], `P` [N/m]."""
    if kind == "hertz":
        profile = fr.Hertz(*shape)
    elif kind == "rounded_flat":
        profile = fr.RoundedFlat(*shape)
    elif kind == "flat":
        profile = fr.FlatPunch(*shape)
    else:
        profile = fr.Gap(*asymmetric_flat(*shape))
    return fr.Contact(profile, E_STAR, f, P)


SHAPES = {
    "hertz": [(0.01,), (0.05,), (0.5,)],
    "rounded_flat": [(2e-4, 0.02), (1e-3, 0.02), (5e-4, 0.1)],
    "flat": [(3e-4,), (2e-3,)],
    "asymmetric": [(5e-4, 0.01, 0.04), (2e-4, 0.05, 0.005), (1e-4, 0.02, 0.2)],
}

#: Profiles whose pressure vanishes at the contact ends (all but the sharp flat punch).
SMOOTH = ["hertz", "rounded_flat", "asymmetric"]


# -- Baseline: the dense active-set solver written by hand -----------------------------------


def baseline_simulate(contact, history, nodes):
    """Method 4 on ``N`` Gauss-Chebyshev points, written the way the field writes it by hand, as a dataset.

    `dense_method4.simulate` (the solver: a dense solve per active-set iteration) on a constant
    normal load, independent of `fretting.models.solver`; the same discretisation, so its
    increments equal the engine's Chebyshev model's. Stick-zone ends are the engine's own sub-grid
    estimate (`fretting.models.method4.stick_zones`) of the slip since each point's episode began,
    so that the two are compared as solvers, not as post-processing.

    Returns
    -------
    xarray.Dataset
        ``Q``, ``sigma``, ``q``, ``slip``, ``stick_start``, ``stick_end``, ``dissipation``,
        ``cycle_dissipation`` over ``step``, ``x``, ``zone``, ``cycle_number``; attributes
        ``a``, ``p0``, ``f``, ``P``, ``E_star``, ``centre``, ``nodes``.
    """
    run = dense_method4.simulate(contact, history, nodes)
    a, t = contact.a, (run.x - contact.centre) / contact.a
    episode_start, zones = np.zeros(nodes), [[(-1.0, 1.0)]]
    for before, slip in itertools.pairwise(run.slip):
        ds, episode = slip - before, before - episode_start
        episode_start = np.where(ds == 0, slip, np.where(np.sign(ds) * np.sign(episode) < 0, before, episode_start))
        zones.append(stick_zones(t, slip - episode_start))
    width = max(len(z) for z in zones)
    ends = np.full((len(zones), width, 2), np.nan)
    for k, z in enumerate(zones):
        ends[k, : len(z)] = z
    ends = contact.centre + a * ends
    cycles = np.zeros(len(history), dtype=int) if history.cycle is None else history.cycle
    return xr.Dataset(
        {
            "Q": ("step", history.Q),
            "sigma": ("step", history.sigma),
            "q": (("step", "x"), run.q),
            "slip": (("step", "x"), run.slip),
            "stick_start": (("step", "zone"), ends[..., 0]),
            "stick_end": (("step", "zone"), ends[..., 1]),
            "dissipation": ("step", run.dissipation),
            "cycle_dissipation": ("cycle_number", np.bincount(cycles, weights=run.dissipation)[1:]),
        },
        coords={"step": np.arange(len(history)), "x": run.x},
        attrs={
            "a": a,
            "p0": contact.p0,
            "f": contact.f,
            "P": contact.P,
            "E_star": contact.E_star,
            "centre": contact.centre,
            "nodes": nodes,
        },
    )


# -- Measurement ------------------------------------------------------------------------------


def measure(compute, repeats):
    """Run `compute` once under tracemalloc, then `repeats` times timed.

    Returns
    -------
    result
        What `compute` returned (first run).
    seconds : float
        Median wall time of the timed runs [s].
    peak : int
        Peak memory traced during the first run [bytes] (Python and NumPy allocations).
    """
    tracemalloc.start()
    try:
        result = compute()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        compute()
        times.append(time.perf_counter() - start)
    return result, float(np.median(times)), peak


def _row(scene, role, label, kwargs, result, seconds, peak, repeats, errors, reference):
    steps = len(scene.history) - 1
    return {
        "scene": scene.name,
        "role": role,
        "label": label,
        "model": "baseline" if role == "baseline" else _model(kwargs),
        "kwargs": json.dumps(kwargs, sort_keys=True),
        "points": int(result.sizes["x"]),
        "steps": steps,
        "repeats": repeats,
        "total_s": seconds,
        "ms_per_step": 1e3 * seconds / steps,
        "peak_MB": peak / 1e6,
        **(errors or dict.fromkeys(ERRORS, math.nan)),
        "reference": reference,
    }


def measure_scene(scene, repeats, quick, log):
    """Rows of every configuration (and the baseline where asked) on `scene`, scored against its reference."""
    rows = []
    every = np.arange(len(scene.history))
    simulate = lambda kwargs: lambda: fr.simulate(scene.contact, scene.history, record=every, **kwargs)  # noqa: E731
    if scene.closed_form:
        reference = accuracy.masing_reference(scene.contact, scene.history)
    else:
        label, kwargs = reference_configuration(quick, scene.baseline)
        result, seconds, peak = measure(simulate(kwargs), 1)
        reference = accuracy.run_reference(result, label)
        rows.append(_row(scene, "reference", label, kwargs, result, seconds, peak, 1, None, label))
        log(f"{scene.name}: reference {label}: {rows[-1]['ms_per_step']:.3g} ms per step")
    for role, (label, kwargs) in [("default", DEFAULT)] + [("engine", c) for c in configurations(quick)]:
        result, seconds, peak = measure(simulate(kwargs), repeats)
        errors = accuracy.score(result, reference)
        rows.append(_row(scene, role, label, kwargs, result, seconds, peak, repeats, errors, reference.label))
        log(_describe(rows[-1]))
    if scene.baseline:
        for label, nodes in baseline_configurations(quick):
            compute = lambda nodes=nodes: baseline_simulate(scene.contact, scene.history, nodes)  # noqa: E731
            result, seconds, peak = measure(compute, repeats)
            errors = accuracy.score(result, reference)
            rows.append(
                _row(
                    scene, "baseline", label, {"nodes": nodes}, result, seconds, peak, repeats, errors, reference.label
                )
            )
            log(_describe(rows[-1]))
    return rows, reference


def _describe(row):
    errors = ", ".join(f"{name} {row[name]:.2e}" for name in ERRORS)
    return f"{row['scene']}: {row['label']}: {row['ms_per_step']:.3g} ms per step, {errors}"


def baseline_ratio(rows):
    """Time of the baseline over the default's on the baseline scene, at equal error.

    Returns
    -------
    dict
        ``low``: against the most expensive baseline that the default equals or beats on every
        error (the default is at least as accurate); ``high``: against the cheapest baseline
        that equals or beats the default on every error. Each ``(label, ratio)`` or None.
    """
    default = next(r for r in rows if r["role"] == "default" and _is_baseline_scene(r, rows))
    baselines = sorted((r for r in rows if r["role"] == "baseline"), key=lambda r: r["total_s"])
    beaten = [r for r in baselines if all(default[e] <= r[e] * EQUAL for e in ERRORS)]
    beating = [r for r in baselines if all(r[e] <= default[e] * EQUAL for e in ERRORS)]
    ratio = lambda r: (r["label"], r["total_s"] / default["total_s"]) if r else None  # noqa: E731
    return {
        "scene": default["scene"],
        "default_ms": default["ms_per_step"],
        "low": ratio(beaten[-1] if beaten else None),
        "high": ratio(beating[0] if beating else None),
    }


def _is_baseline_scene(row, rows):
    return any(r["role"] == "baseline" and r["scene"] == row["scene"] for r in rows)


def steps_scaling(repeats, quick, log):
    """Cost of the default against the number of steps: Hertz Q cycling, only the last step recorded."""
    target = next(t for t in long_targets(quick) if t.name == "hertz_Q_long")
    rows = []
    for cycles in (1, 2, 4) if quick else (1, 4, 16, 64):
        history = target.history(cycles)
        compute = lambda history=history: fr.simulate(target.contact, history, record=[len(history) - 1])  # noqa: E731
        _, seconds, peak = measure(compute, repeats)
        steps = len(history) - 1
        rows.append(
            {
                "cycles": cycles,
                "steps": steps,
                "total_s": seconds,
                "ms_per_step": 1e3 * seconds / steps,
                "peak_MB": peak / 1e6,
            }
        )
        log(f"steps scaling: {steps} steps, {seconds:.3g} s")
    return rows


def resolution_scaling(rows):
    """Cost against resolution on the baseline scene: ms per step and the local exponent ``d ln t / d ln points``."""
    scene = next(r["scene"] for r in rows if r["role"] == "baseline")
    table = []
    for model, group in itertools.groupby(
        sorted(
            (r for r in rows if r["scene"] == scene and r["role"] in ("engine", "baseline", "reference")), key=_order
        ),
        key=lambda r: r["model"],
    ):
        previous = None
        for r in group:
            exponent = math.nan
            if previous and r["points"] != previous["points"]:
                exponent = math.log(r["total_s"] / previous["total_s"]) / math.log(r["points"] / previous["points"])
            table.append(
                {
                    "model": model,
                    "label": r["label"],
                    "points": r["points"],
                    "ms_per_step": r["ms_per_step"],
                    "exponent": exponent,
                    "peak_MB": r["peak_MB"],
                }
            )
            previous = r
    return table


def _order(row):
    return (row["model"], row["points"], row["total_s"])


# -- Long runs --------------------------------------------------------------------------------


def _long_child(spec):
    """Entry point of the subprocess that runs the first cycles of a long target (prints JSON)."""
    spec = json.loads(spec)
    target = next(t for t in long_targets(spec["quick"]) if t.name == spec["target"])
    history = target.history(spec["cycles"])
    start = time.perf_counter()
    result = fr.simulate(target.contact, history, record=[len(history) - 1], **spec["kwargs"])
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # Linux: kB
    print(json.dumps({"seconds": seconds, "peak_rss": peak, "cycle_energy": result.cycle_dissipation.values.tolist()}))


def _run_long_child(target, cycles, kwargs, quick, timeout):
    """Seconds, peak resident memory [bytes] and cycle energies of a child run; None if it timed out."""
    spec = json.dumps({"target": target.name, "cycles": cycles, "kwargs": kwargs, "quick": quick})
    code = f"import sys; sys.path.insert(0, {str(HERE)!r}); import harness; harness._long_child(sys.argv[1])"
    try:
        done = subprocess.run(
            [sys.executable, "-c", code, spec], capture_output=True, text=True, timeout=timeout, check=True
        )
    except subprocess.TimeoutExpired:
        return None
    except subprocess.CalledProcessError as error:
        raise RuntimeError(f"long run {target.name} failed:\n{error.stderr}") from None
    return json.loads(done.stdout.splitlines()[-1])


def long_reference_energies(target, references, cycles):
    """Reference energy of each of the first `cycles` cycles of a long target [J/m].

    The closed form (Masing) over three cycles, or the reference run of the scene with the same
    loads; later cycles repeat the last cycle known (constant amplitude: the state is periodic).
    """
    if target.scene is None:
        known = accuracy.masing_reference(target.contact, target.history(3)).cycle_energy
    else:
        known = references[target.scene].cycle_energy
    return np.concatenate([known[:cycles], np.full(max(cycles - known.size, 0), known[-1])])


def run_long(target, references, quick, timeout, budget, log, estimate=math.inf):
    """Run a long target at default settings, or, when that would take too long, project it.

    Each run is a fresh process (which gives the peak resident memory). The whole history runs
    at once when `estimate` [s] is under half of `timeout` [s]; otherwise runs of 2, 16, 128, ...
    cycles follow while the next takes less than `budget` [s] by the cost growth seen so far, until
    the whole history is expected to fit in half of `timeout`. A whole run that exceeds `timeout`
    is stopped; the result is then projected from the last run made.
    """
    cycles = target.cycles if estimate <= timeout / 2 else min(2, target.cycles)
    runs, stopped = [], False
    while True:
        outcome = _run_long_child(target, cycles, DEFAULT[1], quick, timeout)
        if outcome is None:
            stopped = True
            log(f"{target.name}: {cycles} cycles: stopped after {timeout:g} s")
            break
        runs.append((cycles, outcome))
        log(f"{target.name}: {cycles} cycles in {outcome['seconds']:.3g} s")
        if cycles == target.cycles:
            break
        if _projected(runs, target.cycles) <= timeout / 2:
            cycles = target.cycles
        elif _projected(runs, min(8 * cycles, target.cycles)) <= budget:
            cycles = min(8 * cycles, target.cycles)
        else:
            break
    return _long_row(target, references, runs[-1] if runs else None, timeout, stopped)


def _projected(runs, cycles):
    """Seconds [s] for `cycles` cycles: power law through the last two runs, exponent between 0 and 1."""
    n, outcome = runs[-1]
    exponent = 1.0
    if len(runs) > 1:
        m, before = runs[-2]
        exponent = math.log(max(outcome["seconds"], 1e-9) / max(before["seconds"], 1e-9)) / math.log(n / m)
    return outcome["seconds"] * (cycles / n) ** min(max(exponent, 0.0), 1.0)


def _long_row(target, references, last, timeout, stopped=False):
    row = {
        "target": target.name,
        "title": target.title,
        "cycles": target.cycles,
        "steps": target.cycles * target.steps_per_cycle,
        "limit_s": target.seconds,
        "energy_limit": target.energy,
        "memory_limit_GB": None if target.memory is None else target.memory / 1e9,
    }
    if last is None:
        return row | {"status": f"misses (stopped after {timeout:g} s)", "seconds": math.nan, "run_cycles": 0}
    cycles, outcome = last
    energy = accuracy.energy_error(outcome["cycle_energy"], long_reference_energies(target, references, cycles))
    whole = cycles == target.cycles
    seconds = outcome["seconds"] * (1 if whole else target.cycles / cycles)
    meets = seconds <= target.seconds and (target.energy is None or energy <= target.energy)
    meets = meets and (target.memory is None or outcome["peak_rss"] <= target.memory)
    how = "measured" if whole else f"projected linearly from {cycles} cycles"
    if stopped:
        how += f"; the whole run was stopped after {timeout:g} s"
    return row | {
        "status": f"{'meets' if meets else 'misses'} ({how})",
        "seconds": seconds,
        "run_cycles": cycles,
        "energy_rel": energy,
        "peak_rss_GB": outcome["peak_rss"] / 1e9,
    }


# -- The whole benchmark ------------------------------------------------------------------------


def benchmark(quick=False, repeats=3, long_timeout=60.0, long_budget=20.0, log=None):
    """Measure everything; returns a dict of tables (rows of dicts) and facts about the run."""
    log = log or (lambda message: None)
    start = time.perf_counter()
    rows, references = [], {}
    scene_list = scenes(quick)
    for scene in scene_list:
        scene_rows, references[scene.name] = measure_scene(scene, repeats, quick, log)
        rows += scene_rows
    report = {
        "scenes": [
            (s.name, s.title, len(s.history) - 1, "closed form" if s.closed_form else "most resolved run")
            for s in scene_list
        ],
        "rows": rows,
        "ratio": baseline_ratio(rows),
        "resolution": resolution_scaling(rows),
        "steps": steps_scaling(repeats, quick, log),
        "long": [
            run_long(t, references, quick, long_timeout, long_budget, log, _estimate(t, rows))
            for t in long_targets(quick)
            if LONG_RUNS is None or t.name in LONG_RUNS
        ],
    }
    return report | {"meta": _meta(quick, repeats, time.perf_counter() - start)}


def _estimate(target, rows):
    """Seconds [s] a long target would take at the default's cost per step on the scenes, the slowest."""
    per_step = max(r["ms_per_step"] for r in rows if r["role"] == "default") / 1e3
    return per_step * target.cycles * target.steps_per_cycle


def _meta(quick, repeats, seconds):
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as info:
            cpu = next((line.split(":", 1)[1].strip() for line in info if line.startswith("model name")), cpu)
    except OSError:
        pass
    threads = {name: os.environ.get(name, "unset") for name in ONE_THREAD}
    load = ", ".join(f"{v:.2g}" for v in os.getloadavg())
    return {
        "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "cpu": cpu,
        "cores": os.cpu_count(),
        "threads": ", ".join(f"{k}={v}" for k, v in threads.items()),
        "versions": f"fretting {fr.__version__}, python {platform.python_version()}, numpy {np.__version__}",
        "quick": quick,
        "repeats": repeats,
        "seconds": seconds,
        "load": load,
    }


# -- The Galerkin mesh's adaptive loop, by hand ------------------------------------------------


def increments(scene, Q, sigma=None):
    """Increments of the path ``Q[k], sigma[k]`` from the virgin contact: slip increments and ``g``."""
    sigma = np.zeros_like(Q) if sigma is None else sigma
    slip = np.zeros(scene.x.size)
    ds, g = [], []
    for k in range(1, len(Q)):
        increment = solve_increment(scene.G, scene.g_stuck(Q[k], sigma[k]) - scene.G @ slip, scene.limit)
        slip = slip + increment.ds
        ds.append(increment.ds)
        g.append(increment.g)
    return np.array(ds), np.array(g)


def adapt(contact, Q, sigma=None, rtol=gk.DEFAULT_RTOL, theta=None, passes=30, grading=gk.ENERGY_GRADING):
    """Refine until the mesh stays: the scene, its increments ``ds`` and ``g``, and the number of passes.

    The loop of the Galerkin issue, by hand: run the path ``Q[k], sigma[k]`` [N/m, Pa], reduce
    the element targets of every increment, refine, from `theta` (default
    `fretting.models.galerkin.initial_theta`): the energy stage of
    `fretting.models.galerkin.adaptation.adapted_model`, elements of ``ENERGY_SPAN rtol a``, graded
    around the boundaries by `grading` (`fretting.models.galerkin.element_targets`).
    """
    theta = gk.initial_theta() if theta is None else theta
    for count in range(1, passes + 1):
        scene = gk.Mesh(theta=theta).build(contact)
        ds, g = increments(scene, Q, sigma)
        refined = gk.refine(
            theta, gk.element_targets(theta, ds, rtol, scene.breakpoints, gk.ENERGY_SPAN, gk.ENERGY_SPAN, grading)
        )
        if refined is theta:
            return scene, ds, g, count
        theta = refined
    raise RuntimeError("the mesh did not settle")


def cycles(Q_star, steps):
    """``0 -> Q* -> -Q* -> Q* -> -Q* -> Q*``, `steps` increments a segment; the second cycle is the last 2 segments."""
    vertices = [0.0, Q_star, -Q_star, Q_star, -Q_star, Q_star]
    segments = (np.linspace(u, v, steps + 1)[1:] for u, v in zip(vertices[:-1], vertices[1:], strict=True))
    return np.concatenate([[0.0], *segments])


def cycle_energy(scene, ds, steps):
    """Energy [J/m] dissipated in the second cycle of `cycles` (its last ``2 steps`` increments ``ds``)."""
    return sum(scene.dissipation(row) for row in ds[3 * steps :])


def monotonic(Q_end, steps=4, sigma_end=0.0):
    """``Q`` [N/m] and ``sigma`` [Pa] from zero to `Q_end` and `sigma_end` in `steps` equal increments."""
    return np.linspace(0, Q_end, steps + 1), np.linspace(0, sigma_end, steps + 1)


def ends(scene, slip):
    """Stick zones ``(start, end)`` [m] from the slip of an episode (zero where it stuck)."""
    return scene.contact.centre + scene.contact.a * np.array(stick_zones(scene.t, slip))
