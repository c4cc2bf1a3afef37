"""Speed against error (issue 5): what each engine configuration costs and how right it is.

``fretting bench`` runs every configuration of `configurations` (and the engine's defaults) on
the scenes of `scenes`, times them (median of repeats, one core), scores them against
references and writes ``speed_vs_error.csv``, ``speed_vs_error.png`` and ``speed_vs_error.md``.
Until the command line is wired, ``python -m fretting.bench [--quick] [--out DIR]`` does the same.

Scenes: a Hertz contact under Q cycling (reference: Cattaneo-Mindlin with the Masing rule, the
energy per cycle of Mindlin-Deresiewicz), under in-phase Q and sigma (Nowell-Hills with the
Masing rule), a rounded flat punch under a seeded random Q/sigma path and a Hertz contact under
90-degree out-of-phase Q/sigma (both: the most resolved run, `reference_configuration`), and the
10-vertex random Q/sigma Hertz path on which `baseline_simulate`, the dense active-set method-4
solver the field writes by hand, is timed beside the engine.

Errors, each the largest over the steps (or cycles) of a run:

- stick ends [a]: distance between the stick-zone ends of the run and of the reference (a zone
  only one of them has counts by half its width, `zone_distance`);
- energy per cycle [-]: ``|W / W_ref - 1|``;
- traction [f p0]: ``|q - q_ref|`` at the run's own points, leaving out `BAND` around every
  stick/slip boundary of the reference, those of the step and those its memory keeps (former
  boundaries where locked-in slip starts like ``d^(3/2)``), and inside each contact edge: there
  the traction has square-root kinks.

Only the public interface is used: ``fretting.simulate(contact, history, **kwargs)`` and its
dataset, so any model the engine offers is measured the same way.
"""

import argparse
import csv
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

import numpy as np
import xarray as xr
from scipy import integrate

import fretting as fr
from fretting.models.method4 import stick_zones
from fretting.physics import closed_forms as cf

__all__ = [
    "BAND",
    "DEFAULT",
    "LongTarget",
    "Reference",
    "Scene",
    "add_arguments",
    "baseline_configurations",
    "baseline_simulate",
    "configurations",
    "cycle_energy",
    "energy_error",
    "long_targets",
    "masing_reference",
    "masing_walk",
    "memory_kinks",
    "mindlin_compliance",
    "monotonic_dissipation",
    "reference_configuration",
    "run",
    "run_reference",
    "scenes",
    "score",
    "traction_error",
    "zone_distance",
]

#: Band left out of the traction error around each stick/slip boundary and inside each edge [a].
BAND = 0.02

#: The engine as a user gets it: ``fretting.simulate(contact, history)``.
DEFAULT = ("default", {})

#: Errors within this factor count as equal when the baseline is matched to the default.
EQUAL = 1 + 1e-6

#: Environment that limits BLAS and OpenMP to one thread.
ONE_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}

#: Names of the long targets that `benchmark` runs (None: all of `long_targets`).
LONG_RUNS = None

#: Working-set changes one baseline increment may take before it gives up.
BASELINE_ITERATIONS = 200

#: Rounding allowance of the baseline's friction test, relative to the largest limit.
BASELINE_ROUNDING = 1e-13

ERRORS = ("stick_ends_a", "energy_rel", "traction_fp0")
ERROR_TITLES = {
    "stick_ends_a": "stick-zone ends /a",
    "energy_rel": "energy per cycle (relative)",
    "traction_fp0": "traction /(f p0)",
}


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
        Label and keyword arguments of `fretting.engine.simulation`.
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


# -- Closed forms -----------------------------------------------------------------------------


def _tail(psi, first):
    """``sum_{n >= first} psi^n / (n (n - 1))`` for ``0 <= psi <= 1`` and ``first`` 2 or 3, without cancellation."""
    psi = float(psi)
    if psi < 0.25:
        n = np.arange(first, first + 80)
        return float(np.sum(psi**n / (n * (n - 1.0))))
    two = psi + (1 - psi) * math.log1p(-psi) if psi < 1 else 1.0
    return two if first == 2 else two - psi**2 / 2


def mindlin_compliance(contact, Q):
    """``delta_Q`` [m] of the Cattaneo-Mindlin slip of a Hertz contact under monotonic ``Q`` [N/m].

    ``delta_Q = (1/pi) int_0^pi s(a cos th) dth = (f p0 a / (2 E_star)) (psi + (1 - psi) ln(1 - psi))``,
    ``psi = |Q| / (f P)``, signed as ``Q`` (from ``ds/db = -(2 f p0 b / (E_star a)) arccosh(|x|/b)``).
    """
    psi = abs(Q) / (contact.f * contact.P)
    return math.copysign(contact.f * contact.p0 * contact.a / (2 * contact.E_star) * _tail(psi, 2), Q)


def cycle_energy(contact, Q_star):
    """Energy dissipated per steady cycle between ``+-Q_star`` [J/m] of a Hertz contact (Mindlin-Deresiewicz).

    ``W = 4 Q* dv(Q*) - 8 int_0^Q* dv(u) du`` with ``dv`` = `mindlin_compliance`: the area of the
    Masing loop of ``Q`` against ``delta_Q``.
    """
    Q_star = abs(Q_star)
    area, _ = integrate.quad(lambda u: mindlin_compliance(contact, u), 0.0, Q_star, epsabs=0.0, epsrel=1e-13)
    return 4 * Q_star * mindlin_compliance(contact, Q_star) - 8 * area


def monotonic_dissipation(contact, Q, ratio=0.0):
    """Energy [J/m] dissipated by a Hertz contact loaded from zero along ``sigma = ratio Q`` to ``Q`` [N/m].

    ``int f p |s| dx`` of the Nowell-Hills slip (Cattaneo-Mindlin when ``ratio = 0``): every point
    slips one way only. Closed form for ``ratio = 0``,
    ``(pi f^2 p0^2 a^2 / (4 E_star)) sum_{n>=3} psi^n / (n (n - 1))``; otherwise quadrature.

    Parameters
    ----------
    ratio : float
        ``sigma / Q`` [1/m], within Nowell-Hills' range ``|ratio| <= 2 p0 / P``.
    """
    if ratio == 0.0:
        psi = abs(Q) / (contact.f * contact.P)
        return math.pi * (contact.f * contact.p0 * contact.a) ** 2 / (4 * contact.E_star) * _tail(psi, 3)
    return _slip_work(contact, Q, ratio)


def _slip_work(contact, Q, ratio, order=64):
    """``int f p |s| dx`` [J/m] of the Nowell-Hills slip at ``Q``, ``sigma = ratio Q``, by quadrature.

    Each slip zone, from its stick end ``L`` to the contact edge ``E``, is mapped by
    ``x = L + (E - L) sin^2(phi / 2)``: the ``(x - L)^(3/2)`` of the slip and the
    ``sqrt(E - x)`` of the pressure become analytic in ``phi``, so Gauss-Legendre of `order`
    points converges exponentially: 1e-14 of the closed form at ``Q/(f P) >= 0.2``, 2e-10 at 0.001,
    where the slip formula's own cancellation dominates.
    """
    if Q == 0:
        return 0.0
    a = contact.a
    b = float(cf.stick_half_width(contact, Q))
    e = float(np.sign(Q) * cf.nowell_hills_offset(contact, ratio * Q))
    node, weight = np.polynomial.legendre.leggauss(order)
    phi = np.pi * (node + 1) / 2
    total = 0.0
    for stick_end, edge in ((e + b, a), (e - b, -a)):
        x = stick_end + (edge - stick_end) * np.sin(phi / 2) ** 2
        dx = (edge - stick_end) * np.sin(phi / 2) * np.cos(phi / 2) * np.pi / 2
        slip = np.abs(cf.cattaneo_mindlin_slip(contact, Q, x - e))
        total += np.sum(weight * contact.f * contact.pressure(x) * slip * np.abs(dx))
    return float(total)


@dataclass(frozen=True, eq=False)
class _Monotonic:
    """Hertz contact loaded from zero along ``sigma = ratio Q``: Nowell-Hills (Cattaneo-Mindlin if ``ratio = 0``)."""

    contact: fr.Contact
    ratio: float

    def traction(self, Q, x):
        return cf.nowell_hills_traction(self.contact, Q, self.ratio * Q, x)

    def zone(self, Q):
        """Stick zone ``(start, end)`` [m]."""
        centre = float(np.sign(Q) * cf.nowell_hills_offset(self.contact, self.ratio * Q))
        b = float(cf.stick_half_width(self.contact, Q))
        return centre - b, centre + b

    def dissipation(self, Q, cache):
        key = abs(Q)
        if key not in cache:
            cache[key] = monotonic_dissipation(self.contact, key, self.ratio)
        return cache[key]


# -- Masing reference -------------------------------------------------------------------------


def masing_walk(Q):
    """Turning-point memory of the Masing rule along the load parameter ``Q``.

    The state is a stack of turning points ``Q_1, Q_2, ...``: the path ``0 -> Q_1`` is the
    virgin (monotonic) curve, every later branch ``Q_i -> Q_{i+1}`` is twice the virgin curve at
    half the load change. A branch that reaches the turning point before its own start closes
    its loop: both points leave the stack (the virgin curve's bound is ``-Q_1``).

    Parameters
    ----------
    Q : array_like, shape (n,)
        Load parameter at each step [N/m]; step 0 is the virgin state at ``Q = 0``.

    Returns
    -------
    stacks : list of tuple
        Turning points after each step.
    segments : list of list of tuple
        Branch pieces ``(origin, scale, Q_from, Q_to)`` walked in the increment ending at each
        step, ``scale`` 1 on the virgin curve (origin 0) and 2 after a turning point.
    """
    Q = np.asarray(Q, dtype=float)
    if Q[0] != 0:
        raise ValueError(f"the Masing walk starts from the virgin state Q = 0, found {Q[0]!r}")
    stack, direction = [], 0.0
    stacks, segments = [()], [[]]
    for previous, load in itertools.pairwise(Q.tolist()):
        move = float(np.sign(load - previous))
        walked = []
        if move:
            if direction and move != direction:
                stack.append(previous)
            direction, start = move, previous
            while True:
                origin, scale = (stack[-1], 2) if stack else (0.0, 1)
                bound = stack[-2] if len(stack) > 1 else (-stack[0] if stack else None)
                if bound is not None and (load - bound) * move >= 0:
                    walked.append((origin, scale, start, bound))
                    start = bound
                    del stack[-2:]
                    continue
                walked.append((origin, scale, start, load))
                break
        stacks.append(tuple(stack))
        segments.append(walked)
    return stacks, segments


@dataclass(frozen=True, eq=False)
class Reference:
    """What a run is scored against, per step of the history.

    Attributes
    ----------
    label : str
        "closed form" or the label of the reference run.
    zones : list of ndarray, shape (n_zones, 2)
        Stick zones ``(start, end)`` of the increment ending at each step [m].
    kinks : list of ndarray
        Where the traction has a square-root kink at each step [m]: left out of the traction error.
    cycle_energy : ndarray
        Energy dissipated in each cycle [J/m].
    tractions : callable
        ``tractions(step, x)``: the traction [Pa] at positions ``x`` [m].
    """

    label: str
    zones: list
    kinks: list
    cycle_energy: np.ndarray
    tractions: object


def _proportional_ratio(history):
    """``sigma / Q`` of a proportional history (raises if it is not)."""
    k = int(np.argmax(np.abs(history.Q)))
    ratio = float(history.sigma[k] / history.Q[k])
    if not np.allclose(history.sigma, ratio * history.Q, rtol=1e-12, atol=1e-12 * np.abs(history.sigma).max()):
        raise ValueError("the Masing reference needs proportional loads, sigma = ratio Q")
    return ratio


def masing_reference(contact, history):
    """Closed-form reference of a Hertz contact under proportional loads ``sigma = ratio Q`` from zero.

    The Masing rule over the Nowell-Hills solution (Cattaneo-Mindlin and Mindlin-Deresiewicz
    when ``sigma = 0``): valid while Nowell-Hills is, ``|ratio| <= 2 p0 / P`` and the stick zone
    inside the contact.

    Returns
    -------
    Reference
        Kinks include the stick-zone ends of every branch the memory keeps.
    """
    mono = _Monotonic(contact, _proportional_ratio(history))
    stacks, segments = masing_walk(history.Q)
    cache = {}
    dissipation = np.array([sum(_branch_dissipation(mono, piece, cache) for piece in walk) for walk in segments])
    zones = [np.array([_last_zone(mono, walk)]) for walk in segments]
    paths = [_branches(stack, load) for stack, load in zip(stacks, history.Q.tolist(), strict=True)]
    kinks = [np.array([end for o, s, to in path if to != o for end in mono.zone((to - o) / s)]) for path in paths]

    def tractions(step, x):
        return sum((s * mono.traction((to - o) / s, x) for o, s, to in paths[step]), np.zeros(np.shape(x)))

    energy = np.bincount(history.cycle, weights=dissipation)[1:]
    return Reference("closed form (Masing)", zones, kinks, energy, tractions)


def _branch_dissipation(mono, piece, cache):
    """Energy [J/m] dissipated along a piece ``(origin, scale, Q_from, Q_to)`` of a Masing branch."""
    origin, scale, start, end = piece
    return scale * (mono.dissipation((end - origin) / scale, cache) - mono.dissipation((start - origin) / scale, cache))


def _last_zone(mono, walk):
    """Stick zone [m] of an increment: that of the branch it ends on; the whole contact if nothing moved."""
    if not walk:
        return (-mono.contact.a, mono.contact.a)
    origin, scale, _, end = walk[-1]
    return mono.zone((end - origin) / scale)


def _branches(stack, load):
    """Branches ``(origin, scale, end)`` from the virgin state through the turning points to ``load``."""
    points = [0.0, *stack, load]
    return [(o, 1 if i == 0 else 2, to) for i, (o, to) in enumerate(itertools.pairwise(points))]


def run_reference(result, label):
    """Reference from a (most resolved) run of every step: its stick zones, energies and traction.

    The traction is interpolated linearly. Kinks are the stick-zone ends of the step and the
    boundaries the memory keeps, `memory_kinks`.
    """
    if not np.array_equal(result.step.values, np.arange(result.sizes["step"])):
        raise ValueError("a reference run must record every step")
    zones = [_run_zones(result, k) for k in range(result.sizes["step"])]
    x, q = result.x.values, result.q.values
    kinks = [np.concatenate([z.ravel(), m]) for z, m in zip(zones, memory_kinks(x, result.stick.values), strict=True)]

    def tractions(step, at):
        return np.interp(at, x, q[step])

    return Reference(label, zones, kinks, result.cycle_dissipation.values, tractions)


def memory_kinks(x, stick):
    """Former stick/slip boundaries where the locked-in slip still puts a kink in the traction [m], per step.

    Where a point that slipped at step ``k`` meets one that last slipped before ``k - 1`` (or
    never), the slip of the later episode starts like ``d^(3/2)`` and the traction has a
    square-root kink; a boundary that sweeps outward step by step leaves none. The kink is placed
    midway between the two points.

    Parameters
    ----------
    x : ndarray, shape (N,)
        Positions [m], ascending.
    stick : ndarray of bool, shape (n_steps, N)
        The point did not slip in the increment ending at each step (step 0: the start).

    Returns
    -------
    list of ndarray
    """
    steps = np.arange(stick.shape[0])[:, None]
    last = np.maximum.accumulate(np.where(stick, -2, steps), axis=0)  # -2: never slipped
    middle = (x[1:] + x[:-1]) / 2
    return [middle[np.abs(np.diff(row)) > 1] for row in last]


def _run_zones(result, k):
    """Stick zones ``(start, end)`` [m] of row `k` of a result."""
    pairs = np.stack([result.stick_start.values[k], result.stick_end.values[k]], axis=-1)
    return pairs[~np.isnan(pairs[:, 0])]


# -- Error metrics ----------------------------------------------------------------------------


def zone_distance(zones, reference):
    """Distance [m] between two sets of stick zones, each an array of ``(start, end)`` rows.

    The largest distance an end moves when the ends of `zones` are matched in order to those of
    `reference` (starts to starts, ends to ends), where a zone that one side lacks, a stick zone
    or the slip zone between two stick zones, may instead close up, at half its width: a zone
    that nucleates or vanishes between two discretisations counts by its size, not by its
    distance from the other zones. The smallest such largest distance, by dynamic programming.
    """
    u, v = (np.sort(np.asarray(z, dtype=float).reshape(-1, 2), axis=0).ravel() for z in (zones, reference))
    cost = np.full((u.size + 1, v.size + 1), math.inf)
    cost[0, 0] = 0.0
    for i, j in itertools.product(range(u.size + 1), range(v.size + 1)):
        here = cost[i, j]
        if here == math.inf:
            continue
        if i < u.size and j < v.size and (i - j) % 2 == 0:
            cost[i + 1, j + 1] = min(cost[i + 1, j + 1], max(here, abs(u[i] - v[j])))
        if i + 1 < u.size:
            cost[i + 2, j] = min(cost[i + 2, j], max(here, (u[i + 1] - u[i]) / 2))
        if j + 1 < v.size:
            cost[i, j + 2] = min(cost[i, j + 2], max(here, (v[j + 1] - v[j]) / 2))
    return float(cost[-1, -1])


def energy_error(W, W_ref):
    """Largest ``|W / W_ref - 1|`` over the cycles; ``W_ref`` > 0 [J/m]."""
    W, W_ref = np.asarray(W, dtype=float), np.asarray(W_ref, dtype=float)
    if W.shape != W_ref.shape or np.any(W_ref <= 0):
        raise ValueError(f"need as many cycles, each with positive reference energy, found {W.shape}, {W_ref.shape}")
    return float(np.max(np.abs(W / W_ref - 1), initial=0.0))


def traction_error(x, q, q_ref, exclude, width):
    """Largest ``|q - q_ref|`` [Pa] at the positions ``x`` [m] farther than `width` [m] from all of `exclude` [m].

    Positions where `q` is NaN (a run without a value there) are skipped.
    """
    x = np.asarray(x, dtype=float)
    far = np.all(np.abs(np.subtract.outer(x, np.asarray(exclude, dtype=float).ravel())) > width, axis=-1)
    far &= ~np.isnan(np.asarray(q, dtype=float))
    return float(np.max(np.abs(np.asarray(q) - np.asarray(q_ref))[far], initial=0.0))


def score(result, reference):
    """Errors of a run against a reference: stick ends [a], energy per cycle [-], traction [f p0].

    Every recorded step after the first counts; positions are the run's own.
    """
    attrs = result.attrs
    a, centre, fp0 = attrs["a"], attrs.get("centre", 0.0), attrs["f"] * attrs["p0"]
    x, q = result.x.values, result.q.values
    edges = [centre - a, centre + a]
    stick, traction = 0.0, 0.0
    for k, step in enumerate(result.step.values.tolist()):
        if step == 0:
            continue
        stick = max(stick, zone_distance(_run_zones(result, k), reference.zones[step]))
        exclude = np.concatenate([reference.kinks[step], edges])
        traction = max(traction, traction_error(x, q[k], reference.tractions(step, x), exclude, BAND * a))
    energy = energy_error(result.cycle_dissipation.values, reference.cycle_energy)
    return {"stick_ends_a": stick / a, "energy_rel": energy, "traction_fp0": traction / fp0}


# -- Baseline: the dense active-set solver written by hand -----------------------------------


def baseline_simulate(contact, history, nodes):
    """Method 4 on ``N`` Gauss-Chebyshev points, written the way the field writes it by hand.

    The slip ``s_k`` lives at ``t_k = cos((2k - 1) pi / (2N))``, ``x = centre + a t``, and the
    dislocation kernel is the dense matrix ``G`` of ``sqrt(1 - t_j^2) q_d(t_j) = -sum_k G_jk s_k``,
    ``G = (E_star / (a N)) sum_n n T_n(t_j) T_n(t_k)`` (formulation.md section 4). Each increment
    starts from the previous increment's slip set and iterates: solve ``G_SS ds_S = g_trial_S -
    dir_S f p_S sqrt(1 - t_S^2)`` with `numpy.linalg.solve`, stick the slipping nodes whose slip
    went against its direction, release the stuck nodes whose traction exceeds the friction
    limit, until nothing moves. Independent of `fretting.models.solver`; the same discretisation, so
    its increments equal the engine's Chebyshev model's. Stick-zone ends are the engine's own
    sub-grid estimate (`fretting.engine.simulation.stick_zones`), so that the two are compared as solvers,
    not as post-processing.

    Returns
    -------
    xarray.Dataset
        ``Q``, ``sigma``, ``q``, ``slip``, ``stick_start``, ``stick_end``, ``dissipation``,
        ``cycle_dissipation`` over ``step``, ``x``, ``zone``, ``cycle_number``; attributes
        ``a``, ``p0``, ``f``, ``P``, ``E_star``, ``centre``, ``nodes``.
    """
    a, N = contact.a, nodes
    theta = (2 * np.arange(N, 0, -1) - 1) * np.pi / (2 * N)
    t = np.cos(theta)
    n = np.arange(N)
    T = np.cos(np.outer(theta, n))
    G = contact.E_star / (a * N) * (T * n) @ T.T
    limit = contact.f * contact.pressure_weighted(t)
    tolerance = BASELINE_ROUNDING * limit.max()
    root = np.sqrt(1 - t**2)
    weight = a * np.pi / N
    steps = len(history)
    slip, episode_start, direction = np.zeros(N), np.zeros(N), np.zeros(N)
    q, slips, dissipation = np.zeros((steps, N)), np.zeros((steps, N)), np.zeros(steps)
    zones = [[(-1.0, 1.0)]]
    for k in range(1, steps):
        g_trial = (history.Q[k] / np.pi + history.sigma[k] * a * t / 4) / a - G @ slip
        ds, g, direction = _baseline_increment(G, g_trial, limit, direction, tolerance)
        episode = slip - episode_start
        new_slip = slip + ds
        episode_start = np.where(ds == 0, new_slip, np.where(np.sign(ds) * np.sign(episode) < 0, slip, episode_start))
        slip = new_slip
        q[k], slips[k], dissipation[k] = g / root, slip, weight * np.abs(ds) @ limit
        zones.append(stick_zones(t, slip - episode_start))
    q[0] = (history.Q[0] / np.pi + history.sigma[0] * a * t / 4) / a / root
    width = max(len(z) for z in zones)
    ends = np.full((steps, width, 2), np.nan)
    for k, z in enumerate(zones):
        ends[k, : len(z)] = z
    ends = contact.centre + a * ends
    cycles = np.zeros(steps, dtype=int) if history.cycle is None else history.cycle
    return xr.Dataset(
        {
            "Q": ("step", history.Q),
            "sigma": ("step", history.sigma),
            "q": (("step", "x"), q),
            "slip": (("step", "x"), slips),
            "stick_start": (("step", "zone"), ends[..., 0]),
            "stick_end": (("step", "zone"), ends[..., 1]),
            "dissipation": ("step", dissipation),
            "cycle_dissipation": ("cycle_number", np.bincount(cycles, weights=dissipation)[1:]),
        },
        coords={"step": np.arange(steps), "x": contact.centre + a * t},
        attrs={
            "a": a,
            "p0": contact.p0,
            "f": contact.f,
            "P": contact.P,
            "E_star": contact.E_star,
            "centre": contact.centre,
            "nodes": N,
        },
    )


def _baseline_increment(G, g_trial, limit, direction, tolerance):
    """Iterate the slip set until the friction conditions hold; returns ``ds``, ``g``, the slip directions."""
    direction = direction.copy()
    for _ in range(BASELINE_ITERATIONS):
        slipping = np.flatnonzero(direction)
        if slipping.size == direction.size:
            raise fr.SolverError("baseline: every node slips")
        ds = np.zeros_like(g_trial)
        if slipping.size:
            rhs = g_trial[slipping] - direction[slipping] * limit[slipping]
            ds[slipping] = np.linalg.solve(G[np.ix_(slipping, slipping)], rhs)
        g = g_trial - G @ ds
        backwards = (direction != 0) & (direction * ds < 0)
        released = (direction == 0) & (np.abs(g) - limit > tolerance)
        if not backwards.any() and not released.any():
            return ds, g, direction
        direction[backwards] = 0
        direction[released] = np.sign(g[released])
    raise fr.SolverError(f"baseline: the slip set did not settle in {BASELINE_ITERATIONS} iterations")


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
        reference = masing_reference(scene.contact, scene.history)
    else:
        label, kwargs = reference_configuration(quick, scene.baseline)
        result, seconds, peak = measure(simulate(kwargs), 1)
        reference = run_reference(result, label)
        rows.append(_row(scene, "reference", label, kwargs, result, seconds, peak, 1, None, label))
        log(f"{scene.name}: reference {label}: {rows[-1]['ms_per_step']:.3g} ms per step")
    for role, (label, kwargs) in [("default", DEFAULT)] + [("engine", c) for c in configurations(quick)]:
        result, seconds, peak = measure(simulate(kwargs), repeats)
        rows.append(
            _row(scene, role, label, kwargs, result, seconds, peak, repeats, score(result, reference), reference.label)
        )
        log(_describe(rows[-1]))
    if scene.baseline:
        for label, nodes in baseline_configurations(quick):
            compute = lambda nodes=nodes: baseline_simulate(scene.contact, scene.history, nodes)  # noqa: E731
            result, seconds, peak = measure(compute, repeats)
            errors = score(result, reference)
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
    code = "import sys; from fretting import bench; bench._long_child(sys.argv[1])"
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
        known = masing_reference(target.contact, target.history(3)).cycle_energy
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
    energy = energy_error(outcome["cycle_energy"], long_reference_energies(target, references, cycles))
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


# -- Writers ------------------------------------------------------------------------------------

CSV_COLUMNS = (
    "scene", "role", "label", "model", "kwargs", "points", "steps", "repeats", "total_s", "ms_per_step", "peak_MB",
    *ERRORS, "reference",
)  # fmt: skip


def write_csv(rows, path):
    """One row per scene and configuration."""
    with open(path, "w", newline="") as file:
        writer = csv.DictWriter(file, CSV_COLUMNS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: f"{v:.6g}" if isinstance(v, float) else v for k, v in row.items()})
    return path


def write_png(rows, path):
    """Error against time per step, log-log, one panel per error; lines join one model's configurations."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.ticker import NullFormatter

    figure = Figure(figsize=(14, 4.6), layout="constrained")
    axes = figure.subplots(1, len(ERRORS))
    names = list(dict.fromkeys(r["scene"] for r in rows))
    colours = dict(zip(names, matplotlib.colormaps["tab10"].colors, strict=False))
    for ax, error in zip(axes, ERRORS, strict=True):
        for (name, model), group in itertools.groupby(
            sorted(
                (r for r in rows if r["role"] in ("engine", "baseline")),
                key=lambda r: (r["scene"], r["model"], r["points"]),
            ),
            key=lambda r: (r["scene"], r["model"]),
        ):
            group = [r for r in group if r[error] > 0]
            style = (
                {"ls": "--", "marker": "x", "mfc": "none"}
                if model == "baseline"
                else {"ls": "-", "marker": "o", "ms": 4}
            )
            label = f"{name} ({model})" if model != "chebyshev" else name
            ax.plot(
                [r["ms_per_step"] for r in group], [r[error] for r in group], color=colours[name], label=label, **style
            )
        for r in rows:
            if r["role"] == "default" and r[error] > 0:
                ax.plot(r["ms_per_step"], r[error], "*", color=colours[r["scene"]], ms=13, mec="k", mew=0.6)
        ax.set(xscale="log", yscale="log", xlabel="wall time per step [ms], one core", title=ERROR_TITLES[error])
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7, title="lines: configurations; star: default", title_fontsize=7)
    figure.savefig(path, dpi=130)
    return path


def _fmt(value, spec=".2e"):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return format(value, spec)


def _table(header, lines):
    out = [
        "| " + " | ".join(header) + " |",
        "|" + "|".join(" ---: " if i else " --- " for i in range(len(header))) + "|",
    ]
    return out + ["| " + " | ".join(str(cell) for cell in line) + " |" for line in lines]


def _field_table(rows, columns):
    """`_table` of the dicts `rows`; `columns` are ``(header, key, format)``, format None: the value as it is.

    A key a row lacks (a measurement not made) shows as ``-``.
    """
    header = tuple(title for title, _, _ in columns)
    cells = [[_fmt(row.get(key), spec or "") for _, key, spec in columns] for row in rows]
    return _table(header, cells)


def markdown(report, png_name):
    """The short report: how it was measured, one table per scene, the baseline, scaling, long runs."""
    meta, ratio = report["meta"], report["ratio"]
    lines = [
        "# Speed against error",
        "",
        f"`fretting bench{' --quick' if meta['quick'] else ''}`, {meta['date']}, {meta['cpu']} "
        f"({meta['cores']} cores), one core ({meta['threads']}); {meta['versions']}. "
        f"Times are medians of {meta['repeats']} runs "
        f"(references: one run); peak memory is what tracemalloc saw in a separate run. The benchmark took "
        f"{meta['seconds']:.0f} s; load average at the end {meta['load']} (other processes share the cores).",
        "",
        "Errors are the largest over the steps (cycles) of a run: **stick ends** `/a`, distance between the "
        "stick-zone ends and the reference's (a zone, stick or slip, that only one of them has counts by half "
        "its width); **energy**, `|W/W_ref - 1|` per cycle; **traction** `/(f p0)`, "
        f"`|q - q_ref|` at the run's own points, leaving out {BAND} a around each stick/slip boundary of the "
        "reference, those of the step and those its memory keeps (square-root kinks of the traction), and "
        "inside each contact edge. References of runs are interpolated linearly to the run's points.",
        "",
        f"![error against time per step]({png_name})",
        "",
        *_table(("scene", "history", "steps", "reference"), report["scenes"]),
    ]
    for name in dict.fromkeys(r["scene"] for r in report["rows"]):
        lines += ["", f"## {name}", ""]
        scene_rows = [r for r in report["rows"] if r["scene"] == name]
        lines += _table(
            ("configuration", "points", "ms/step", "total s", "peak MB", "stick ends /a", "energy", "traction /fp0"),
            [
                (
                    f"**{r['label']}**"
                    if r["role"] == "default"
                    else f"{r['label']}{' (reference)' if r['role'] == 'reference' else ''}",
                    r["points"],
                    _fmt(r["ms_per_step"], ".3g"),
                    _fmt(r["total_s"], ".3g"),
                    _fmt(r["peak_MB"], ".3g"),
                    *(_fmt(r[e]) for e in ERRORS),
                )
                for r in scene_rows
            ],
        )
    lines += ["", "## Baseline", "", _ratio_text(ratio), "", "## Cost against resolution", ""]
    lines += _field_table(
        report["resolution"],
        [("model", "model", None), ("configuration", "label", None), ("points", "points", None),
         ("ms/step", "ms_per_step", ".3g"), ("exponent d ln t / d ln N", "exponent", ".2f"),
         ("peak MB", "peak_MB", ".3g")],
    )  # fmt: skip
    lines += ["", "## Cost against steps (default, Hertz Q cycling, last step recorded)", ""]
    lines += _field_table(
        report["steps"],
        [("cycles", "cycles", None), ("steps", "steps", None), ("total s", "total_s", ".3g"),
         ("ms/step", "ms_per_step", ".3g"), ("peak MB", "peak_MB", ".3g")],
    )  # fmt: skip
    lines += ["", "## Long runs (default settings, fresh process each)", ""]
    lines += _field_table(
        report["long"],
        [("target", "target", None), ("history", "title", None), ("cycles", "cycles", None),
         ("steps", "steps", None), ("time s", "seconds", ".3g"), ("limit s", "limit_s", "g"),
         ("energy", "energy_rel", ".2e"), ("limit", "energy_limit", "g"), ("peak RSS GB", "peak_rss_GB", ".3g"),
         ("status", "status", None)],
    )  # fmt: skip
    lines += [
        "",
        "Projected times are linear in the cycles from the longest run made; its energy error and peak memory are "
        "those of that run. Reference energies: the Masing closed form, or (out of phase) the reference run of the "
        "first three cycles, whose last cycle repeats.",
    ]
    return "\n".join(lines) + "\n"


def _ratio_text(ratio):
    parts = [f"On `{ratio['scene']}` the default takes {ratio['default_ms']:.3g} ms per step."]
    if ratio["low"]:
        label, value = ratio["low"]
        parts.append(
            f"The most resolved baseline it equals or beats on every error, {label}, takes **{value:.3g} x** as long."
        )
    else:
        parts.append("The default is less accurate than every baseline measured on some error.")
    if ratio["high"]:
        label, value = ratio["high"]
        parts.append(
            f"The cheapest baseline that equals or beats it on every error, {label}, takes {value:.3g} x as long."
        )
    else:
        parts.append("No baseline measured reaches the default's errors: the ratio at equal error is larger still.")
    return " ".join(parts)


def write_md(report, path, png_name):
    path.write_text(markdown(report, png_name))
    return path


# -- Command line -------------------------------------------------------------------------------


def add_arguments(parser):
    """Options of ``fretting bench``."""
    parser.add_argument("--out", default="results", metavar="DIR", help="directory of the outputs (default: results)")
    parser.add_argument("--quick", action="store_true", help="small scenes and few configurations: a smoke test")
    parser.add_argument(
        "--repeats", type=int, default=None, help="timed runs per configuration (default 3; 1 with --quick)"
    )
    parser.add_argument(
        "--long-timeout",
        type=float,
        default=None,
        metavar="SECONDS",
        help="longest long run (default 60; 20 with --quick)",
    )
    parser.add_argument(
        "--any-threads",
        action="store_true",
        help="time with the BLAS threads as they are (default: rerun with one thread)",
    )
    return parser


def run(args):
    """Run the benchmark as `args` say; write the CSV, PNG and MD; return the exit code."""
    if not args.any_threads and any(os.environ.get(name) != "1" for name in ONE_THREAD):
        command = [sys.executable, "-m", "fretting.bench", *_argv(args)]
        return subprocess.call(command, env=os.environ | ONE_THREAD)
    repeats = args.repeats if args.repeats is not None else (1 if args.quick else 3)
    timeout = args.long_timeout if args.long_timeout is not None else (20.0 if args.quick else 60.0)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    log = lambda message: print(message, file=sys.stderr, flush=True)  # noqa: E731
    report = benchmark(args.quick, repeats, timeout, timeout / 3, log)
    stem = out / "speed_vs_error"
    written = [
        write_csv(report["rows"], stem.with_suffix(".csv")),
        write_png(report["rows"], stem.with_suffix(".png")),
        write_md(report, stem.with_suffix(".md"), stem.with_suffix(".png").name),
    ]
    for path in written:
        print(path)
    return 0


def _argv(args):
    argv = ["--out", str(args.out), "--any-threads"]
    argv += ["--quick"] if args.quick else []
    argv += [] if args.repeats is None else ["--repeats", str(args.repeats)]
    return argv + ([] if args.long_timeout is None else ["--long-timeout", str(args.long_timeout)])


def main(argv=None):
    """``python -m fretting.bench``."""
    parser = add_arguments(argparse.ArgumentParser(prog="fretting bench", description=__doc__.splitlines()[0]))
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
