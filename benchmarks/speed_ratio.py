"""The default against a dense method-4 code at equal error: the speed ratio of issue 34, scene by scene.

Run:  python benchmarks/speed_ratio.py [--quick] [--page PATH] [--truth N] [--scenes NAME ...]
      (writes docs/validation/speed-ratio.md when every scene is run in full)
      (about 15 minutes of CPU on one core; --quick, a smoke run of fewer nodes, shorter scenes and 1
      repeat: under a minute; --truth, a finer truth than `TRUTH_NODES`; --scenes, some of them)

Against another checkout: ``PYTHONPATH=<checkout> python benchmarks/speed_ratio.py`` (this folder
is found next to the script; only ``fretting.simulate(contact, history)`` and the fields of its
dataset are used). ``import speed_ratio`` gives the pieces: `scenes`, `from_result`, `stick_zones`,
`score`, `measure_scene`.

On each scene of `scenes`, the default (``fretting.simulate(contact, history)``, default settings)
and `dense_method4.simulate` scanned over ``N`` are scored against the truth, the dense code at
`TRUTH_NODES` (its difference from the finest ``N`` scanned is printed: the truth's own error is
below it where the scan converges). Errors, each the largest over every step of the history (no
step skipped), the same measure applied to both codes from the fields they record (`Run`):

- **energy**: the energy dissipated up to each step, relative to the truth's, over the steps whose
  truth has dissipated at least `ENERGY_FLOOR` of the whole history's;
- **stick ends** [a of the step]: `fretting.analysis.accuracy.zone_distance` between the stick zones
  that `stick_zones` locates under the grid (the ``3/2`` power law of the slip next to a stick end)
  in each run;
- **slip**, as the trajectories benchmark holds it and the README promises it: ``|s - s_true|`` at
  the run's points in contact over the truth's largest ``|s|`` of the whole history at every step,
  and over the truth's largest of the step after the first `harness.FIRST_STEPS` steps (whose slip
  zones are slivers at the contact edges: their largest slip is under about 1 % of what follows);
- **traction** [f p0]: ``|q - q_true|`` at the run's points, leaving out `accuracy.BAND` a around
  the truth's stick ends, the stick/slip boundaries its memory keeps, the contact edges and, where ``P``
  varies, the edges of the contacts of the steps before (the traction of a band that entered kinks there).

The truth is interpolated linearly to each run's points. For each scene and measure: the cheapest
``N`` from which every finer ``N`` scanned equals or beats the default's error, and its CPU time
over the default's (the ratio the issue asks to be >= 10); "all" is the ``N`` that does so for
every measure at once. CPU time (`time.process_time`) of one core, BLAS and OpenMP on one thread
(`threadpoolctl`), the median of `REPEATS` runs for the default and each matching ``N`` (one run
for the other ``N``, to find them).
"""

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import dense_method4  # noqa: E402
import harness  # noqa: E402
import numpy as np  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

import fretting as fr  # noqa: E402
from fretting.analysis import accuracy  # noqa: E402
from fretting.models.method4 import deficit_end  # noqa: E402

HERE = Path(__file__).resolve().parent

#: Node counts of the dense code scanned, and the truth's (quick mode: fewer).
NODES, TRUTH_NODES = (64, 96, 128, 192, 256, 384, 512, 768, 1024, 1536, 2048), 3072
QUICK_NODES, QUICK_TRUTH = (32, 64, 128, 256), 512

#: Parts of a step of the truth where P varies, finer than the dense code's scanned (`dense_method4.LOAD_PART`,
#: the package's default): the implicit parts converge about linearly in their size.
TRUTH_LOAD_PART = dense_method4.LOAD_PART / 4

#: Timed runs of the default and of each matching N (the median is reported).
REPEATS = 3

#: Steps whose truth has dissipated less than this fraction of the whole history's energy are not
#: scored for energy: a relative error of almost nothing says nothing.
ENERGY_FLOOR = 1e-3

#: Errors within this factor count as equal.
EQUAL = 1 + 1e-6

MEASURES = {
    "energy": "energy to each step (relative)",
    "ends": "stick ends [a]",
    "slip_history": "slip [largest of the history]",
    "slip_step": f"slip [largest of the step, after step {harness.FIRST_STEPS}]",
    "traction": "traction [f p0]",
}


# -- Scenes -----------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Scene:
    """A contact and a load history."""

    name: str
    title: str
    contact: fr.Contact
    history: fr.History


def random_walk(contact, vertices, steps_per_segment, seed, Q_range=0.8, sigma_range=1.0, P_range=None):
    """Seeded random vertices from zero: ``Q/(f P)`` in ``[-Q_range, Q_range)``, ``sigma/(f p0)`` in
    ``[-sigma_range, sigma_range)``, and with `P_range` ``P/P_0`` in ``[1 - P_range, 1 + P_range)``."""
    rng = np.random.default_rng(seed)
    Q = rng.uniform(-Q_range, Q_range, vertices) * contact.f * contact.P
    sigma = rng.uniform(-sigma_range, sigma_range, vertices) * contact.f * contact.p0
    Q[0] = sigma[0] = 0.0
    P = None
    if P_range is not None:
        P = rng.uniform(1 - P_range, 1 + P_range, vertices) * contact.P
        P[0] = contact.P
    return fr.History.piecewise_linear(Q, sigma, steps_per_segment, P=P)


def scenes(quick=False):
    """The five scenes of issue 34 (shorter in quick mode)."""
    hertz, flat = harness.hertz_contact(), harness.rounded_flat_contact()
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    steps, per_cycle = (3, 16) if quick else (12, 64)
    ellipse = fr.History.sinusoidal(0.5 * fP, 0.8 * fp0, 90.0, cycles=2, steps_per_cycle=per_cycle)
    b_over_a = flat.profile.b / flat.a
    return [
        Scene("hertz_walk_0", f"Hertz, 10 random Q/sigma vertices (seed 0), {steps} steps a segment",
              hertz, random_walk(hertz, 10, steps, seed=0)),
        Scene("hertz_walk_1", f"Hertz, 10 random Q/sigma vertices (seed 1), {steps} steps a segment",
              hertz, random_walk(hertz, 10, steps, seed=1)),
        Scene("hertz_ellipse", f"Hertz, Q = 0.5 fP sin, sigma = 0.8 f p0 sin(+90 deg), 2 cycles of {per_cycle} "
              "steps", hertz, ellipse),
        Scene("flat_walk", f"rounded flat (b/a = {b_over_a:.2f}), 10 random Q/sigma vertices (seed 2), {steps} "
              "steps a segment", flat, random_walk(flat, 10, steps, seed=2, Q_range=0.7, sigma_range=0.5)),
        Scene("hertz_P_walk", f"Hertz, 8 random (P, Q, sigma) vertices (seed 3, P within 15 %), {steps} steps a "
              "segment", hertz, random_walk(hertz, 8, steps, seed=3, Q_range=0.5, sigma_range=0.5, P_range=0.15)),
    ]  # fmt: skip


# -- The fields of a run, and the errors -------------------------------------------------------


def from_result(result, contact, history):
    """The `dense_method4.Run` of a dataset of `fretting.simulate` that recorded every step."""
    if not np.array_equal(result.step.values, np.arange(len(history))):
        raise ValueError("the run must record every step")
    x, steps = result.x.values, len(history)
    if "p_step" in result:
        p = result.p_step.values
    else:
        p = np.broadcast_to(contact.pressure(x), (steps, x.size))
    a = result.a.values if "a" in result else np.full(steps, result.attrs["a"])
    centre = np.full(steps, result.attrs.get("centre", 0.0))
    q, slip, stick = result.q.values, result.slip.values, result.stick.values
    return dense_method4.Run(x, q, slip, p, stick, result.dissipation.values, a, centre, contact.f, contact.p0)


def episode_slip(run):
    """Slip [m] of each point since its current episode began, at every step, shape (n_steps, N).

    An episode is the slip of a point in one direction: it begins when the point starts to slip
    after sticking, or reverses.
    """
    start, episodes = np.zeros(run.x.size), np.zeros_like(run.slip)
    for k in range(1, run.slip.shape[0]):
        before, slip = run.slip[k - 1], run.slip[k]
        ds = slip - before
        start = np.where(ds == 0, slip, np.where(np.sign(ds) * np.sign(before - start) < 0, before, start))
        episodes[k] = slip - start
    return episodes


def stick_zones(run, k, episodes):
    """Stick zones ``(start, end)`` [m] of the increment ending at step `k` >= 1, shape (n, 2).

    A stick zone is a run of points in contact (pressure above zero) that did not slip in the
    increment; its ends lie between its last point and the slipping point next to it. Next to a
    stick end ``e`` the slip grows as ``|x - e|^(3/2)`` (its gradient, the dislocation density, as
    the square root: the classical behaviour at a stick/slip boundary, as in Cattaneo-Mindlin, eq
    19 of the seed paper): the slip of the increment next to an end that advanced in it, the slip
    of the episode (`episodes`, of `episode_slip`) next to one that stayed. So ``|s|^(2/3)`` is
    linear in ``x``: of the two slips, the one whose ``|s|^(2/3)`` is nearer a line through the
    three slipping points next to the zone is extrapolated from the first two to zero, and kept
    between the zone's last point and its slipping neighbour; where fewer than two points slip there,
    the friction deficit ``f p - s q`` of the zone's last two points (``s`` the sign of the slipping
    neighbour's traction) is, by its square-root law (`_kink`). A zone that reaches the last point in
    contact ends where the deficit of its last two points, against the sign of the last one's traction,
    extrapolates to zero between it and the contact edge (`_kink`; a slip zone narrower than the spacing
    there), or at the edge.
    """
    inside = np.flatnonzero(run.p[k] > 0)
    x = run.x[inside]
    laws = [np.abs(s[inside]) ** (2 / 3) for s in (run.slip[k] - run.slip[k - 1], episodes[k])]
    stuck = run.stick[k, inside].astype(int)
    q, limit = run.q[k, inside], run.f * run.p[k, inside]
    deficit = lambda j: limit - np.sign(q[j]) * q  # noqa: E731  (against the limit of the sign of q at j)
    edges = (run.centre[k] - run.a[k], run.centre[k] + run.a[k])
    change = np.flatnonzero(np.diff(np.concatenate([[0], stuck, [0]])))
    zones = []
    for first, stop in zip(change[::2], change[1::2], strict=True):
        if first == 0:
            start = _kink(x, deficit(0), 0, -1, edges[0], edges[0])
        else:
            start = _end(x, laws, deficit(first - 1), first, -1)
        if stop == x.size:
            end = _kink(x, deficit(-1), x.size - 1, 1, edges[1], edges[1])
        else:
            end = _end(x, laws, deficit(stop), stop - 1, 1)
        zones.append((start, end))
    return np.array(zones).reshape(-1, 2)


def _end(x, laws, deficit, i, side):
    """Where the ``|s|^(2/3)`` of `laws` that is straightest at the three points past the stick
    point `i` on `side` (+1, -1), linear through the first two, reaches zero, within ``[x_i, x_(i +
    side)]``; where fewer than two points slip there, or neither law grows away from the zone, the
    `_kink` of the traction's `deficit` (the middle of the two points where that does not place it)."""
    o, beyond, third = i + side, i + 2 * side, i + 3 * side
    found, straightest = None, np.inf
    for v in laws if 0 <= beyond < x.size else ():
        if v[beyond] <= v[o]:
            continue
        slope = (v[beyond] - v[o]) / (x[beyond] - x[o])
        bend = abs(v[o] + slope * (x[third] - x[o]) - v[third]) / v[third] if 0 <= third < x.size else np.inf
        if bend < straightest or found is None:
            found, straightest = x[o] - v[o] / slope, bend
    if found is None:
        return _kink(x, deficit, i, side, x[o], (x[i] + x[o]) / 2)
    return float(np.clip(found, min(x[i], x[o]), max(x[i], x[o])))


def _kink(x, deficit, i, side, bound, otherwise):
    """Where the square of the friction `deficit` [Pa] of the stick points `i` and ``i - side`` (the stick
    zone's side) reaches zero (`fretting.models.method4.deficit_end`, the square-root kink), within ``[x_i,
    bound]``; the same law holds next to a contact edge that a band entered stuck at the ratio ``r`` of shear to
    pressure, where the deficit ``(f - r) p`` reaches zero at the edge. `otherwise` where the deficit does not
    fall towards the end."""
    found = deficit_end(x, deficit, i, i - side)
    if found is None:
        return otherwise
    return float(np.clip(found, min(x[i], bound), max(x[i], bound)))


@dataclass(frozen=True, eq=False)
class Truth:
    """The truth's fields and what the errors leave out, per step."""

    run: dense_method4.Run
    zones: list
    kinks: list
    energy: np.ndarray

    @classmethod
    def of(cls, run):
        whole = np.array([[run.centre[0] - run.a[0], run.centre[0] + run.a[0]]])
        episodes = episode_slip(run)
        zones = [whole] + [stick_zones(run, k, episodes) for k in range(1, run.q.shape[0])]
        memory = accuracy.memory_kinks(run.x, run.stick)
        lower, upper = run.centre - run.a, run.centre + run.a
        edges = [np.concatenate([lower[: k + 1], upper[: k + 1]]) for k in range(run.a.size)]
        kinks = [np.concatenate([z.ravel(), m, e]) for z, m, e in zip(zones, memory, edges, strict=True)]
        return cls(run, zones, kinks, np.cumsum(run.dissipation))


def score(run, truth):
    """Errors of `run` against `truth` (a `Truth`), each the largest over the steps: a dict of `MEASURES`."""
    fp0 = run.f * run.p0
    scored = truth.energy >= ENERGY_FLOOR * truth.energy[-1]
    energy = np.abs(np.cumsum(run.dissipation)[scored] / truth.energy[scored] - 1)
    errors = dict.fromkeys(MEASURES, 0.0) | {"energy": float(energy.max(initial=0.0))}
    t, episodes = truth.run, episode_slip(run)
    largest = [np.abs(slip[p > 0]).max(initial=0.0) for slip, p in zip(t.slip, t.p, strict=True)]
    for k in range(1, run.q.shape[0]):
        inside = np.abs(run.x - run.centre[k]) < run.a[k]
        ends = accuracy.zone_distance(stick_zones(run, k, episodes), truth.zones[k]) / run.a[k]
        slip = np.abs(run.slip[k, inside] - np.interp(run.x[inside], t.x, t.slip[k])).max(initial=0.0)
        slip_history = slip / max(largest) if max(largest) > 0 else 0.0
        slip_step = slip / largest[k] if k > harness.FIRST_STEPS and largest[k] > 0 else 0.0
        q_true = np.interp(run.x, t.x, t.q[k])
        traction = accuracy.traction_error(run.x, run.q[k], q_true, truth.kinks[k], accuracy.BAND * run.a[k]) / fp0
        for name, value in (
            ("ends", ends),
            ("slip_history", slip_history),
            ("slip_step", slip_step),
            ("traction", traction),
        ):
            errors[name] = max(errors[name], value)
    return errors


# -- Measurement ------------------------------------------------------------------------------


def cpu(compute):
    """``(value, CPU seconds)`` of `compute()` on one BLAS thread."""
    with threadpool_limits(1):
        start = time.process_time()
        value = compute()
        return value, time.process_time() - start


def median_cpu(compute, first, repeats):
    """Median CPU time [s] of `repeats` runs of which `first` [s] is the first."""
    return float(np.median([first] + [cpu(compute)[1] for _ in range(repeats - 1)]))


def matching(rows, default, measures):
    """The cheapest row from which every finer row has each of `measures` at most the default's; None if none."""
    found = None
    for row in reversed(rows):
        if not all(row["errors"][m] <= default["errors"][m] * EQUAL for m in measures):
            break
        found = row
    return found


def measure_scene(scene, nodes, truth_nodes, repeats, log):
    """The default, the dense scan and the truth on `scene`: a dict of rows and matches."""
    steps = len(scene.history) - 1
    run_default = lambda: fr.simulate(scene.contact, scene.history)  # noqa: E731
    result, seconds = cpu(run_default)
    default = {"label": "default", "model": result.attrs.get("model", "?"), "points": int(result.sizes["x"])}
    default["seconds"] = median_cpu(run_default, seconds, repeats)
    log(f"{scene.name}: default ({default['model']}, {default['points']} points) {default['seconds']:.3g} s")
    dense = lambda n: lambda: dense_method4.simulate(scene.contact, scene.history, n)  # noqa: E731
    truth_run, truth_seconds = cpu(
        lambda: dense_method4.simulate(scene.contact, scene.history, truth_nodes, TRUTH_LOAD_PART)
    )
    truth = Truth.of(truth_run)
    log(f"{scene.name}: truth N = {truth_nodes} {truth_seconds:.3g} s")
    parts = None
    if scene.history.P is not None:  # the truth's resolution in its parts: twice as long parts against it
        run, seconds = cpu(
            lambda: dense_method4.simulate(scene.contact, scene.history, truth_nodes, 2 * TRUTH_LOAD_PART)
        )
        parts = {"label": f"N = {truth_nodes}, parts x 2", "nodes": truth_nodes, "seconds": seconds}
        parts["errors"] = score(run, truth)
        log(f"{scene.name}: truth with parts twice as long: " + _errors_text(parts["errors"]))
    default["errors"] = score(from_result(result, scene.contact, scene.history), truth)
    log(f"{scene.name}: default " + _errors_text(default["errors"]))
    rows = []
    for n in nodes:
        run, seconds = cpu(dense(n))
        rows.append({"label": f"N = {n}", "nodes": n, "seconds": seconds, "errors": score(run, truth)})
        log(f"{scene.name}: N = {n} {seconds:.3g} s " + _errors_text(rows[-1]["errors"]))
    matches = {m: matching(rows, default, [m]) for m in MEASURES} | {"all": matching(rows, default, list(MEASURES))}
    for row in {id(r): r for r in matches.values() if r is not None}.values():
        row["seconds"] = median_cpu(dense(row["nodes"]), row["seconds"], repeats)
        row["timed"] = repeats
    return {
        "scene": scene,
        "steps": steps,
        "default": default,
        "rows": rows,
        "truth_nodes": truth_nodes,
        "truth_seconds": truth_seconds,
        "parts": parts,
        "matches": matches,
    }


def _errors_text(errors):
    return ", ".join(f"{m} {errors[m]:.2e}" for m in MEASURES)


# -- Report -------------------------------------------------------------------------------------


def resolution(s, measure):
    """The truth's own resolution in `measure` on scene `s`: the finest N scanned against it, and
    where P varies its run with parts twice as long, the larger."""
    errors = [s["rows"][-1]["errors"][measure]] + ([s["parts"]["errors"][measure]] if s["parts"] else [])
    return max(errors)


def summary_rows(measured):
    """One row per scene and measure: default's error, matching N, ratio, the truth's own resolution."""
    rows = []
    for s in measured:
        default, finest = s["default"], s["rows"][-1]
        for m in (*MEASURES, "all"):
            row = s["matches"][m]
            error = None if m == "all" else default["errors"][m]
            truth = None if m == "all" else resolution(s, m)
            rows.append(
                {
                    "scene": s["scene"].name,
                    "measure": m,
                    "default_error": error,
                    "nodes": None if row is None else row["nodes"],
                    "ratio": None if row is None else row["seconds"] / default["seconds"],
                    "beyond": finest["nodes"],
                    "floor": finest["seconds"] / default["seconds"],
                    "truth": truth,
                    "below_truth": error is not None and error < truth,
                }
            )
    return rows


def _ratio_text(row):
    if row["nodes"] is None:
        return f"> N = {row['beyond']}", f"> {row['floor']:.3g}"
    return f"{row['nodes']}", f"{row['ratio']:.3g}"


def markdown(measured, meta):
    """The generated page: how it was measured, the summary, the scan of each scene."""
    measure_titles = MEASURES | {"all": "all measures together"}
    finest = measured[0]["rows"][-1]["nodes"]
    lines = [
        "# Speed ratio against a dense method-4 code",
        "",
        '!!! info "Generated"',
        f"    {meta['versions']}, {meta['date']}, by `python benchmarks/speed_ratio.py{meta['flags']}` (regenerate "
        f"with that command from the repository root); {meta['cpu']}, CPU time of one core (one BLAS thread), "
        f"medians of {meta['repeats']}; the run took {meta['seconds']:.0f} s, load average {meta['load']} at its end.",
        "",
        "The default (`fretting.simulate(contact, history)`, default settings) against `benchmarks/dense_method4.py`, "
        "method 4 on N Chebyshev-Gauss points with one dense solve per active-set iteration (about 150 lines of "
        f"NumPy). Both are scored against the dense code at N = {measured[0]['truth_nodes']} at every step, from the "
        "fields each records, by the same measures (`benchmarks/speed_ratio.py`): the energy dissipated up to each "
        f"step (relative, steps past {ENERGY_FLOOR:g} of the total), the stick-zone ends located under the grid by the "
        "3/2 power law of the slip next to them [a], the slip [the history's largest at every step, the step's "
        f"largest after step {harness.FIRST_STEPS}, as the trajectories benchmark and the README hold it] and the "
        "traction away from "
        f"{accuracy.BAND} a of stick/slip boundaries and edges [f p0].",
        "",
        "**N** is the cheapest scanned from which every finer N equals or beats the default's error; **ratio** its "
        "CPU time over the default's (the target of issue 34: at least 10 on every scene, all measures together). "
        f"'> N = {finest}': no N scanned reaches the default's error, the ratio is larger than that of N = {finest}. "
        f"**truth's resolution** is the error of N = {finest} against the truth (where P varies, also that of the "
        f"truth's N with parts of a step twice as long, {2 * TRUTH_LOAD_PART:.3g} of P against "
        f"{TRUTH_LOAD_PART:.3g}; the scan's parts are {dense_method4.LOAD_PART:.3g}, the package's default): an error "
        "of the default below it (marked \\*) is not resolved by the truth, and neither is its N.",
        "",
        *_table(
            ("scene", "history", "steps", "default: model, points, CPU s"),
            [
                (
                    s["scene"].name,
                    s["scene"].title,
                    s["steps"],
                    f"{s['default']['model']}, {s['default']['points']}, {s['default']['seconds']:.3g}",
                )
                for s in measured
            ],
        ),  # fmt: skip
        "",
        "## Summary",
        "",
    ]
    lines += _table(
        ("scene", "measure", "default's error", "truth's resolution", "N", "ratio"),
        [
            (
                r["scene"],
                measure_titles[r["measure"]],
                _fmt(r["default_error"]) + (" \\*" if r["below_truth"] else ""),
                _fmt(r["truth"]),
                *_ratio_text(r),
            )
            for r in summary_rows(measured)
        ],
    )
    for s in measured:
        lines += ["", f"## {s['scene'].name}", "", s["scene"].title, ""]
        default = s["default"]
        table = [("**default**", default["points"], _fmt(default["seconds"], ".3g"), *_error_cells(default))]
        extra = [s["parts"]] if s["parts"] else []
        table += [(r["label"], r["nodes"], _fmt(r["seconds"], ".3g"), *_error_cells(r)) for r in s["rows"] + extra]
        lines += _table(("run", "points", "CPU s", *MEASURES.values()), table)
    return "\n".join(lines) + "\n"


def _error_cells(row):
    return [_fmt(row["errors"][m]) for m in MEASURES]


def _fmt(value, spec=".2e"):
    return "-" if value is None or (isinstance(value, float) and math.isnan(value)) else format(value, spec)


def _table(header, lines):
    out = [
        "| " + " | ".join(header) + " |",
        "|" + "|".join(" ---: " if i else " --- " for i in range(len(header))) + "|",
    ]
    return out + ["| " + " | ".join(str(cell) for cell in line) + " |" for line in lines]


def _meta(quick, repeats, seconds):
    return harness._meta(quick, repeats, seconds)


def benchmark(quick=False, repeats=None, log=None, truth_nodes=None, names=None, flags=""):
    """The scenes `names` (None: all) measured: ``(measured, meta)``; `truth_nodes` None: the mode's."""
    log = log or (lambda message: None)
    repeats = repeats if repeats is not None else (1 if quick else REPEATS)
    nodes, truth = (QUICK_NODES, QUICK_TRUTH) if quick else (NODES, TRUTH_NODES)
    truth_nodes = truth_nodes or truth
    chosen = [scene for scene in scenes(quick) if names is None or scene.name in names]
    start = time.perf_counter()
    measured = [measure_scene(scene, nodes, truth_nodes, repeats, log) for scene in chosen]
    return measured, _meta(quick, repeats, time.perf_counter() - start) | {"flags": flags}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer N, shorter scenes, 1 repeat: a smoke run")
    parser.add_argument("--repeats", type=int, default=None, help=f"timed runs (default {REPEATS}; 1 with --quick)")
    parser.add_argument(
        "--page",
        default=None,
        help="generated page (default: docs/validation/speed-ratio.md for a full run of every scene, none for "
        "--quick or --scenes, whose figures are not the page's; '-': none)",
    )
    parser.add_argument("--truth", type=int, default=None, metavar="N", help=f"the truth's N (default {TRUTH_NODES})")
    names = [scene.name for scene in scenes()]
    parser.add_argument("--scenes", nargs="+", choices=names, default=None, help="these scenes only (default: all)")
    args = parser.parse_args(argv)
    if args.truth is not None and args.truth <= max(QUICK_NODES if args.quick else NODES):
        parser.error(f"--truth must be above the finest N scanned, found {args.truth}")
    print(f"fretting {fr.__version__} from {Path(fr.__file__).parent}", file=sys.stderr)
    log = lambda message: print(message, file=sys.stderr, flush=True)  # noqa: E731
    flags = " --quick" * args.quick + "".join(
        f" --{name} {value}" for name, value in (("repeats", args.repeats), ("truth", args.truth)) if value is not None
    )
    flags += f" --scenes {' '.join(args.scenes)}" if args.scenes else ""
    measured, meta = benchmark(args.quick, args.repeats, log, args.truth, args.scenes, flags)
    text = markdown(measured, meta)
    print(text[text.index("## Summary") :].split("\n## ")[0])
    if args.page is None and not (args.quick or args.scenes):
        args.page = HERE.parent / "docs" / "validation" / "speed-ratio.md"
    if args.page not in (None, "-"):
        page = Path(args.page)
        partial = page.with_suffix(".partial")
        partial.write_text(text)
        partial.replace(page)
        print(f"wrote {page}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
