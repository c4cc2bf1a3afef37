"""Accuracy of the varying-load model (`fretting.models.Varying`) at every step, against a converged reference.

Histories (`SCENES`), on the Hertz contact of `harness.hertz_contact` and the rounded flat of
`harness.rounded_flat_contact`:

- ``walk``: a seeded random walk of (P, Q, sigma), P in [0.7, 1.3] of the contact's, Q within 0.6 f P,
  sigma within 0.3 f p0 (``walk0``: the same with ``sigma = 0``);
- ``inphase``: the loops ``P = P0 (1 + 0.3 sin)``, ``Q = r 0.3 f P0 sin``, three cycles at ``r = 0.95``
  then three at ``r = 1.05`` (``|dQ/dP|`` near ``f``: below it the contact shakes down, above it does not);
- ``boundary``: in-phase loops at ``|dQ/dP| = 0.98 f``, then 1.02 f, about a mean shear ``0.3 f P0``;
- ``recede``: Cattaneo-Mindlin at ``Q = 0.45 f P0``, the load down to ``0.6 P0`` (the contact recedes past
  the slip zones), ``Q`` reversed, the load up to ``1.3 P0`` (it grows over them again) and back;
- ``inphase_sigma``, ``boundary_sigma``, ``recede_sigma``: the same with a bulk tension in phase with the shear,
  ``sigma / (f p0) = TENSION Q / (f P0)``, the shear lowered so that the edge the tension loads most sees the
  scene's increments of the fully stuck traction (`tensioned`): the loops stay as near the shakedown boundary.

Reference. With ``sigma = 0``: Jaeger's superposition (`fretting.physics.superposition`, which the default runs
there: `fretting.models.Jaeger`), exact to rounding in its stick ends, slip, traction and energy on Hertz, and on
the rounded flat to the convergence of its quadratures (tests/physics/test_superposition.py). With ``sigma``:
method 4 on twice the scored run's cells with parts a quarter of its, shown converged by the run on four times
its cells (`references`): the change between the two is printed, and must lie well below the targets; where it
does not, the reference is not converged, and the scored run's figures estimate its error from below only where
the error falls steadily with the cells (the reference then errs the same way, by less).

Figures, each the worst over the steps of a history (`compare`):

- stick ends [a of the step's contact]: `fretting.analysis.accuracy.zone_distance` between the stick zones, as
  the trajectories benchmark and the speed-ratio page measure them (their ends matched in order; a zone that
  one run has and the other lacks counts by half its width);
- slip: at the step's nodes in contact, over the reference's largest there, as the README and the trajectories
  benchmark hold it (over the history's largest at the first `harness.FIRST_STEPS` steps, whose slip zones are
  slivers at the edges, and where the step has no slip);
- increment: the slip of the step at the nodes in contact at both of its ends (against the self-reference,
  those between its own nodes in contact: beyond them its ``slip`` is the free surfaces' relative
  displacement), over its largest (over the history's largest where the step slips by less than `SLIVER` of
  that). A harsher measure: next to a stick end that advances by ``dc`` in a step the increment grows as
  ``sqrt(|x - c|) dc``, so an end placed ``e`` off errs there by about ``sqrt(h / w) e / dc`` of the step's
  largest (``h`` the spacing, ``w`` the slip zone's width);
- traction [f p0], leaving out `accuracy.BAND` a about the contact edges, the reference's stick ends at their
  signed positions and the former edges and stick ends the memory keeps (exact: where ``lambda`` jumps by more
  than `KINK` f; self-reference: every stick end and contact edge of the steps so far);
- energy dissipated up to each step, over the reference's total for the history.

Targets: `TARGETS`.

Rows: ``cells``, method 4 on the cells of `Varying` (`--cells`, `--load-part`: the default's with ``sigma``);
without ``sigma`` also the default, which there is the exact model (its stick ends differ from the reference's
by where `ExactRun` reads them: from the slip, at `SLIVER`).

    python benchmarks/varying_accuracy.py [--scenes walk0,inphase,...] [--flat-scenes walk,...] [--cells 768]
        [--load-part 0.0025] [--no-fine] [--no-finer] [--page ../docs/validation/varying-load.md]
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from harness import FIRST_STEPS, hertz_contact, rounded_flat_contact

import fretting as fr
from fretting.analysis.accuracy import BAND, run_zones, zone_distance
from fretting.models.normal import DEFAULT_CELLS, DEFAULT_LOAD_PART, Varying
from fretting.physics.superposition import Superposition, geometry

#: Targets at every step: stick ends [a], slip and its increment in the step [of the step's largest], traction
#: [f p0], energy [relative].
TARGETS = {"stick": 1e-3, "slip": 1e-3, "increment": 1e-3, "traction": 1e-3, "energy": 1e-4}

#: Slip [of the step's largest] below which the exact solution's slip zone counts as stuck (`ExactRun._end`).
SLIVER = 1e-6

#: Jumps of ``lambda`` [f] that put a kink in the exact traction (left out of the traction error).
KINK = 1e-2

#: Bulk tension of the ``_sigma`` scenes [f p0] per shear [f P0] (`tensioned`).
TENSION = 0.5

STEPS = 16  # per cycle or segment


def _history(P, Q, sigma, cycle_length=None):
    n = len(P)
    vertex = np.arange(0, n, STEPS)
    if cycle_length is None:
        number = np.zeros(n, dtype=np.int64)
    else:
        number = np.concatenate([[0], (np.arange(1, n) - 1) // cycle_length + 1])
    return fr.History(np.asarray(Q, float), np.asarray(sigma, float), vertex, number, np.asarray(P, float))


def walk(contact, sigma=True, seed=7, segments=6):
    rng = np.random.default_rng(seed)
    P0, fP0, fp0 = contact.P, contact.f * contact.P, contact.f * contact.p0
    P = np.concatenate([[1.0], rng.uniform(0.7, 1.3, segments)]) * P0
    Q = np.concatenate([[0.0], rng.uniform(-0.6, 0.6, segments) * P[1:] / P0]) * fP0
    s = np.concatenate([[0.0], rng.uniform(-0.3, 0.3, segments)]) * fp0 * sigma
    path = fr.History.piecewise_linear(Q, s, STEPS, P=P)
    return _history(path.P, path.Q, path.sigma)


def tensioned(contact, Q, tension):
    """``(Q, sigma)`` [N/m, Pa]: the shear `Q` [N/m] of a scene with a bulk tension in phase with it,
    ``sigma / (f p0) = tension Q / (f P0)``, and the shear lowered by ``1 + k``, ``k = (pi a / 4) tension p0 / P0``
    (the contact's ``a``, ``p0``, ``P0``): the increment of the fully stuck traction ``dQ + (pi a / 4) dsigma``
    (eqs 9, 20) at the edge the tension loads most is then the scene's ``dQ``, which Jaeger's rule weighs against
    ``f dP`` (`fretting.models.normal.NormalModel.edges_slip`), the contact's own ``a`` standing for the load's."""
    k = np.pi * contact.a / 4 * tension * contact.p0 / contact.P
    Q = np.asarray(Q, float) / (1 + k)
    return Q, tension * contact.p0 / contact.P * Q


def inphase(contact, cycles=3, tension=0.0):
    theta = 2 * np.pi * np.arange(2 * cycles * STEPS + 1) / STEPS
    r = np.where(np.arange(theta.size) <= cycles * STEPS, 0.95, 1.05)
    P = contact.P * (1 + 0.3 * np.sin(theta))
    return _history(P, *tensioned(contact, r * 0.3 * contact.f * contact.P * np.sin(theta), tension), STEPS)


def boundary(contact, cycles=2, tension=0.0):
    """``Q`` to ``0.3 f P0`` at ``P0``, then loops ``P = P0 (1 + 0.25 sin)``, ``dQ = r f dP``: `cycles` at
    ``r = 0.98``, then `cycles` at 1.02 (with a `tension`: `tensioned`)."""
    ramp = np.linspace(0, 1, STEPS + 1)
    theta = 2 * np.pi * np.arange(1, 2 * cycles * STEPS + 1) / STEPS
    r = np.where(np.arange(1, theta.size + 1) <= cycles * STEPS, 0.98, 1.02)
    fP0 = contact.f * contact.P
    P = contact.P * np.concatenate([np.ones(ramp.size), 1 + 0.25 * np.sin(theta)])
    Q = fP0 * np.concatenate([0.3 * ramp, 0.3 + r * 0.25 * np.sin(theta)])
    return _history(P, *tensioned(contact, Q, tension), STEPS)


def recede(contact, tension=0.0):
    P0, fP0 = contact.P, contact.f * contact.P
    P = [P0, P0, 0.6 * P0, 0.6 * P0, 1.3 * P0, P0]
    Q = [0.0, 0.45 * fP0, 0.45 * fP0, -0.3 * fP0, -0.3 * fP0, 0.2 * fP0]
    path = fr.History.piecewise_linear(Q, None, STEPS, P=P)
    return _history(path.P, *tensioned(contact, path.Q, tension))


#: name: history builder (of a contact); where the history has no sigma, the reference is the exact one
SCENES = {
    "walk0": lambda c: walk(c, sigma=False),
    "walk": walk,
    "inphase": inphase,
    "boundary": boundary,
    "recede": recede,
    "inphase_sigma": lambda c: inphase(c, tension=TENSION),
    "boundary_sigma": lambda c: boundary(c, tension=TENSION),
    "recede_sigma": lambda c: recede(c, tension=TENSION),
}


class ExactRun:
    """Jaeger's solution at every step of a history, as the arrays `compare` reads."""

    def __init__(self, contact, history):
        jaeger = Superposition(geometry(contact.profile, contact.E_star, contact.f), contact.P)
        self.memory, self.stick, self.energy = [jaeger.memory], [jaeger.memory.a], [0.0]
        for P, Q in zip(history.P[1:], history.Q[1:], strict=True):
            step = jaeger.advance(float(P), float(Q))
            self.memory.append(jaeger.memory)
            self.stick.append(jaeger.memory.a if step.stick is None else self._end(step.stick))
            self.energy.append(self.energy[-1] + step.energy)
        self.energy = np.array(self.energy)

    def _end(self, c):
        """The stick end [m] of the last step: the innermost ``|x|`` past `c` where its slip exceeds `SLIVER` of
        its largest.

        A slip zone whose inner end passes bands already at the limit slips there by nothing; one that reaches
        just past them, into a band below the limit, moves the end of Jaeger's stick zone there while the slip
        beyond grows by a sliver's worth: the end read from the slip is where a method 4 grid can see it."""
        before, after = self.memory[-2], self.memory[-1]
        x = np.linspace(c, min(before.a, after.a), 4001)
        ds = np.abs(after.slip(x) - before.slip(x))
        over = np.flatnonzero(ds > SLIVER * ds.max())
        if over.size == 0 or over[0] == 0:
            return c
        low, high = x[over[0] - 1], x[over[0]]
        for _ in range(40):
            middle = (low + high) / 2
            low, high = (
                (low, middle) if abs(after.slip(middle) - before.slip(middle)) > SLIVER * ds.max() else (middle, high)
            )
        return float(high)

    def slip(self, k, x):
        return self.memory[k].slip(x)

    def increment(self, k, x):
        return self.memory[k].slip(x) - self.memory[k - 1].slip(x)

    def traction(self, k, x):
        return self.memory[k].traction(x)

    def zones(self, k):
        """The stick zone [m] of step `k`, ``(start, end)`` rows (symmetric: ``sigma = 0``; none where it slides)."""
        return np.array([[-self.stick[k], self.stick[k]]]) if self.stick[k] > 0 else np.zeros((0, 2))

    def avoid(self, k, f):
        """Where the traction of step `k` may kink [m]: its stick ends and the band edges where ``lambda`` jumps."""
        kinks = self.memory[k].kinks(KINK * f)
        return np.concatenate([self.zones(k).ravel(), kinks, -kinks])


class PackageRun:
    """A run of the package read as the reference (`compare`): stick ends, slip, traction, energy per step."""

    def __init__(self, result):
        self.result = result
        self.energy = np.cumsum(result.dissipation.values)
        self._x = result.x.values

    def slip(self, k, x):
        """The slip [m] at step `k` at the points `x` [m], interpolated between the run's nodes in contact then;
        NaN beyond them, where the run has no slip to compare (the ``slip`` of a node out of contact is the
        relative displacement of the free surfaces there)."""
        return self._between(np.abs(self._x) < self.result.a.values[k], self.result.slip.values[k], x)

    def increment(self, k, x):
        """The slip increment [m] of step `k` at the points `x` [m], between the run's nodes in contact at both
        ends of the step (`slip`)."""
        r = self.result
        inside = np.abs(self._x) < min(r.a.values[k], r.a.values[k - 1])
        return self._between(inside, r.slip.values[k] - r.slip.values[k - 1], x)

    def _between(self, inside, values, x):
        return np.interp(x, self._x[inside], values[inside], left=np.nan, right=np.nan)

    def traction(self, k, x):
        return np.interp(x, self._x, self.result.q.values[k])

    def zones(self, k):
        """The stick zones [m] of step `k`, ``(start, end)`` rows."""
        return run_zones(self.result, k)

    def avoid(self, k, f):
        """Where the traction of step `k` may kink [m]: the ends of its stick zones, and those of every earlier step
        and the edges of the contacts met (where the memory may kink)."""
        r = self.result
        starts, ends = r.stick_start.values[: k + 1], r.stick_end.values[: k + 1]
        zones = np.concatenate([starts[~np.isnan(starts)], ends[~np.isnan(ends)]])
        return np.concatenate([zones, r.a.values[:k], -r.a.values[:k]])


def compare(result, reference, contact):
    """Worst figures over the steps of `result` against `reference` (`ExactRun` or `PackageRun`), as `TARGETS`."""
    x, a, q = result.x.values, result.a.values, result.q.values
    fp0, worst = contact.f * contact.p0, dict.fromkeys(TARGETS, 0.0)
    where = dict.fromkeys(TARGETS, 0)
    own = PackageRun(result)
    history_increment = max(
        np.nanmax(np.abs(reference.increment(k, x[np.abs(x) < min(a[k], a[k - 1])])), initial=0.0)
        for k in range(1, result.sizes["step"])
    )
    history_slip = max(
        np.nanmax(np.abs(reference.slip(k, x[np.abs(x) < a[k]])), initial=0.0) for k in range(result.sizes["step"])
    )
    for k in range(1, result.sizes["step"]):
        figures = {"stick": zone_distance(own.zones(k), reference.zones(k)) / a[k]}
        inside, expected = _where_known(reference.slip, k, np.flatnonzero(np.abs(x) < a[k]), x)
        largest = np.max(np.abs(expected), initial=0.0) if k > FIRST_STEPS else 0.0
        error = np.max(np.abs(result.slip.values[k, inside] - expected), initial=0.0)
        figures["slip"] = error / (largest or history_slip) if error else 0.0
        both, expected = _where_known(reference.increment, k, np.flatnonzero(np.abs(x) < min(a[k], a[k - 1])), x)
        largest = np.max(np.abs(expected), initial=0.0)
        found = result.slip.values[k, both] - result.slip.values[k - 1, both]
        figures["increment"] = np.max(np.abs(found - expected), initial=0.0) / (
            largest if largest > SLIVER * history_increment else history_increment
        )
        avoid = np.concatenate([[-a[k], a[k]], reference.avoid(k, contact.f)])
        band = (np.abs(x) < a[k]) & np.all(np.abs(x[:, None] - avoid) > BAND * a[k], axis=1)
        figures["traction"] = np.max(np.abs(q[k, band] - reference.traction(k, x[band])), initial=0.0) / fp0
        figures["energy"] = abs(own.energy[k] - reference.energy[k]) / reference.energy[-1]
        for name, value in figures.items():
            if value > worst[name]:
                worst[name], where[name] = float(value), k
    return worst, where


def _where_known(field, k, nodes, x):
    """The `nodes` where the reference's `field` (``slip`` or ``increment``) of step `k` is known, and its values
    there."""
    values = field(k, x[nodes])
    known = ~np.isnan(values)
    return nodes[known], values[known]


def line(label, worst, where, seconds=None):
    flags = {name: "*" if worst[name] > TARGETS[name] else " " for name in TARGETS}
    cells = " ".join(f"{worst[n]:9.2e}{flags[n]}({where[n]:3d})" for n in TARGETS)
    time_ = "" if seconds is None else f" {seconds:7.2f}"
    return f"  {label:<28}{cells}{time_}"


def references(cells, part):
    """``(cells, load_part)`` of the self-reference of a run on `cells` cells in parts of `part`, and of the finer run
    that shows it converged: twice and four times the cells, a quarter of the parts."""
    return (2 * cells, part / 4), (4 * cells, part / 4)


def run(contact, history, cells, part):
    start = time.process_time()
    result = fr.simulate(contact, history, model=Varying(cells, load_part=part))
    return result, time.process_time() - start


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", default=",".join(SCENES), help="on Hertz")
    parser.add_argument("--flat-scenes", default=",".join(SCENES), help="on the rounded flat")
    parser.add_argument("--cells", type=int, default=DEFAULT_CELLS)
    parser.add_argument("--load-part", type=float, default=DEFAULT_LOAD_PART)
    parser.add_argument("--no-finer", action="store_true", help="skip the finer run (the self-reference's check)")
    parser.add_argument("--no-fine", action="store_true", help="skip the self-reference's run against the exact one")
    parser.add_argument("--page", type=Path, help="also write the output to this Markdown page")
    args = parser.parse_args(argv)
    fine_spec, finer_spec = references(args.cells, args.load_part)
    out = []

    def say(text=""):
        print(text, flush=True)
        out.append(text)

    say(f"varying-load model: worst figures over the steps (step in brackets; * over target) of Varying({args.cells},")
    say(f"load_part={args.load_part:g}); targets {TARGETS}")
    say(f"  {'run':<28}" + "".join(f"{name:>16}" for name in TARGETS) + "  CPU [s]")
    contacts = {"hertz": hertz_contact(), "flat": rounded_flat_contact()}
    for profile, names in (("hertz", args.scenes), ("flat", args.flat_scenes)):
        contact = contacts[profile]
        for name in filter(None, names.split(",")):
            history = SCENES[name](contact)
            say(f"{profile} {name}: {len(history) - 1} steps")
            result, seconds = run(contact, history, args.cells, args.load_part)
            if not history.sigma.any():
                reference = ExactRun(contact, history)
                say(line("cells vs exact", *compare(result, reference, contact), seconds))
                if not args.no_fine:
                    fine, fine_seconds = run(contact, history, *fine_spec)
                    say(line(f"Varying{fine_spec} vs exact", *compare(fine, reference, contact), fine_seconds))
                start = time.process_time()
                default = fr.simulate(contact, history)
                default_seconds = time.process_time() - start
                say(line(f"default ({default.attrs['model']}) vs exact", *compare(default, reference, contact),
                         default_seconds))  # fmt: skip
            else:
                fine, fine_seconds = run(contact, history, *fine_spec)
                reference = PackageRun(fine)
                say(line(f"cells vs Varying{fine_spec}", *compare(result, reference, contact), seconds))
                if not args.no_finer:
                    finer, finer_seconds = run(contact, history, *finer_spec)
                    say(line(f"{fine_spec} vs {finer_spec}", *compare(fine, PackageRun(finer), contact), finer_seconds))
    if args.page:
        args.page.write_text(page(out, argv))
    return 0


def page(lines, argv):
    """The docs page: what is measured (this module's docstring) and the table printed."""
    command = " ".join(["python benchmarks/varying_accuracy.py", *(argv if argv is not None else sys.argv[1:])])
    text = __doc__.split("\n\n    python")[0]
    return (
        "# Accuracy under a varying normal load\n\n"
        f"Generated by `{command}` (run from `benchmarks/`); do not edit by hand.\n\n"
        f"{text.split(chr(10), 1)[1].strip()}\n\n```text\n" + "\n".join(lines) + "\n```\n"
    )


if __name__ == "__main__":
    sys.exit(main())
