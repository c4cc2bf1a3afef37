"""Service lives through `fretting run`: CPU time, peak memory and energy error of long random histories.

The targets of issue 21, on the contact of `histories/hertz_shear_cycling.toml` under a
`random` block (16 steps a segment, 32 a cycle, seed 1; ``Q_amplitude = 40e3``, 0.57 f P, and,
in phase, ``sigma_amplitude = 1e8``, 0.53 f p0), each run at default settings by `fretting run`
in a fresh process, on one BLAS thread:

- random in-phase Q and sigma, the default model: energy per cycle against a run solving every
  step (``--every-step``) of the first `PREFIX` cycles (a prefix of the same draws). The default
  there is the exact in-phase model (`fretting.models.InPhase`), so this compares it with itself;
  its error against a converged method-4 run is printed by
  ``benchmarks/inphase_accuracy.py --service-life``;
- the same on the fixed grid of `GRID` nodes, against ``--every-step`` on that grid: the cost
  of the steps alone and the error of skipping them;
- random Q alone, the default (the exact model): energy per cycle against the Masing walk of
  the Mindlin-Deresiewicz closed form over every cycle (`masing_energy`);
- peak memory of each at 10 times fewer cycles, to show that it grows with the cycles only by the
  history's loads (histories past 625 cycles record the same 8192 steps);
- 10^6 cycles: run with ``--million``, else the CPU time extrapolated;
- in-phase sinusoids (a `sine` block, `SINE_STEPS` steps a cycle, the amplitudes above): their
  cycles repeat and are copied, so the rows show the memory of the history itself (held by one
  cycle), at 10^4 cycles and 10^5 (10^6 with ``--million``); the energy of the last cycle against
  that of the 10^4 run's;
- non-periodic out-of-phase cycles (``--out-of-phase`` alone: `out_of_phase_blocks`, every step
  solved on method 4's mesh), `OUT_OF_PHASE` cycles at default settings and 10^4 extrapolated:
  the energy per cycle of the first `PREFIX_OUT_OF_PHASE` against those cycles on a mesh of
  ``rtol`` `FINE_RTOL`. Histories this short (under 20000 steps) record every step, so their
  peak memory grows with the recorded fields.

The table ends each row with the issue's target and whether it is met ("?" where the row does not
give that figure).

CPU time is the child's user + system time and peak memory its maximum resident set
(`resource.getrusage` of a wrapper process that runs only that child). Cycles beyond those run
are extrapolated linearly in the cycles, and printed as such.

Run:  python benchmarks/service_life.py [--short] [--Q-alone] [--million] [--out-of-phase]   (--short:
10^3 cycles in phase and 10^4 of Q alone, two minutes; default 10^4 and 10^5, about 15 minutes;
--Q-alone: the rows of Q alone only; --million: 10^6 cycles of each as well, half an hour more;
--out-of-phase: those rows only, ten minutes)
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import fretting as fr
from fretting.loading.examples import example_path
from fretting.physics.closed_forms import cattaneo_mindlin_dissipation, masing_increment

EXAMPLE = example_path("hertz_shear_cycling")
Q_AMPLITUDE, SIGMA_AMPLITUDE, STEPS_PER_SEGMENT, SEED = 40e3, 1e8, 16, 1

#: Nodes of the fixed grid run beside the default (that of its fallback): the cost of the steps
#: alone, without the default's mesh adaptation.
GRID = 384

#: Cycles of the reference run that solves every step: a prefix of the same draws.
PREFIX = 200

#: Cycles of the out-of-phase rows run, of their reference, and its rtol (the default's is 1e-4).
OUT_OF_PHASE, PREFIX_OUT_OF_PHASE, FINE_RTOL = (100, 300), 20, 3e-5

#: Steps a cycle of the periodic rows (a `sine` block, whose cycles repeat and are copied).
SINE_STEPS = 64

#: A child that runs `fretting run` with the arguments given and prints its CPU time and peak memory.
WRAPPER = """
import json, resource, subprocess, sys
subprocess.run([sys.executable, "-m", "fretting", "run", *sys.argv[1:]], check=True, stdout=subprocess.DEVNULL)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"cpu": usage.ru_utime + usage.ru_stime, "peak": usage.ru_maxrss * 1024}))
"""

ONE_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}


def history_text(cycles, sigma, kind="random"):
    """The example's contact under `cycles` cycles as a history file: random in-phase cycles (with
    bulk tension if `sigma`); `kind` "sine": in-phase sinusoids of the same amplitudes, `SINE_STEPS`
    steps a cycle; "out_of_phase": `out_of_phase_blocks`."""
    contact = tomllib.loads(EXAMPLE.read_text())["contact"]
    lines = ["[contact]", *(f"{key} = {value!r}" for key, value in contact.items()), ""]
    if kind == "out_of_phase":
        return "\n".join([*lines, *out_of_phase_blocks(cycles)])
    lines += ["[[loading]]", f"kind = {kind!r}", f"cycles = {cycles}", f"Q_amplitude = {Q_AMPLITUDE}"]
    if kind == "random":
        lines += [f"seed = {SEED}", f"steps_per_segment = {STEPS_PER_SEGMENT}"]
    else:
        lines += [f"steps_per_cycle = {SINE_STEPS}"]
    lines += [f"sigma_amplitude = {SIGMA_AMPLITUDE}"] if sigma else []
    return "\n".join([*lines, ""])


def out_of_phase_blocks(cycles):
    """History-file blocks of `cycles` non-periodic out-of-phase cycles: cycle ``k`` goes round the
    octagon ``(A_k cos(theta), B_k sin(theta))``, ``theta = 2 pi j / 8``, ``A_k / Q_AMPLITUDE`` and
    ``B_k / SIGMA_AMPLITUDE`` drawn uniformly from [0.5, 1) (seed `SEED`), `STEPS_PER_SEGMENT` / 4
    steps a segment (32 a cycle), after a first loading to ``(A_1, 0)``; one block a cycle."""
    amplitude = np.random.default_rng(SEED).random((cycles, 2)) * 0.5 + 0.5
    theta = 2 * np.pi * np.arange(1, 9) / 8
    steps = f"steps_per_segment = {STEPS_PER_SEGMENT // 4}"
    lines = ["[[loading]]", 'kind = "linear"', f"Q = [{float(Q_AMPLITUDE * amplitude[0, 0])!r}]", steps, ""]
    for A, B in amplitude:
        Q, sigma = (
            ", ".join(map(repr, values.tolist()))
            for values in (Q_AMPLITUDE * A * np.cos(theta), SIGMA_AMPLITUDE * B * np.sin(theta))
        )
        lines += ["[[loading]]", 'kind = "linear"', f"Q = [{Q}]", f"sigma = [{sigma}]", steps, "cycle = true", ""]
    return lines


def run(folder, cycles, sigma, *options, kind="random"):
    """``(result file, cpu seconds, peak bytes)`` of `fretting run` on `cycles` cycles of `kind` (`history_text`)."""
    source = folder / f"{kind}_{'in_phase' if sigma else 'Q_alone'}_{cycles}{'_'.join(['', *options])}.toml"
    source.write_text(history_text(cycles, sigma, kind))
    output = source.with_suffix(".h5")
    command = [sys.executable, "-c", WRAPPER, str(source), "-o", str(output), *options]
    found = subprocess.run(command, check=True, capture_output=True, text=True, env=os.environ | ONE_THREAD)
    usage = json.loads(found.stdout)
    return output, usage["cpu"], usage["peak"]


def masing_energy(source):
    """Energy [J/m] of each cycle of the Q-alone history file `source` from closed forms: the
    Masing walk of its vertices (`masing_increment`), each branch piece dissipating ``k (E(|Q_end -
    origin| / k) - E(|Q_start - origin| / k))`` with ``E`` the Cattaneo-Mindlin energy of
    monotonic loading (`cattaneo_mindlin_dissipation`, of all pieces at once) and ``k`` the
    branch's factor, summed per cycle in the order walked."""
    contact, history = fr.read_history(source)
    turning, before, walked = (), 0.0, []  # (cycle, factor, |Q_end - origin|, |Q_start - origin|) of each piece
    loads, _, cycles, _ = history.at(history.vertex_step[1:])  # the vertices only: a long history forms no more
    for Q, cycle in zip(loads.tolist(), cycles.tolist(), strict=True):
        turning, pieces = masing_increment(turning, before, Q)
        walked += [(cycle, factor, abs(end - origin), abs(start - origin)) for origin, factor, start, end in pieces]
        before = Q
    cycle, factor, end, start = np.array(walked).T
    virgin = (cattaneo_mindlin_dissipation(contact, load / factor) for load in (end, start))
    energy = np.zeros(history.cycle_count + 1)
    np.add.at(energy, cycle.astype(np.int64), factor * (next(virgin) - next(virgin)))
    return energy[1:]


def worst(energy, reference):
    """Largest relative error of the energies per cycle."""
    return float(np.max(np.abs(energy / reference - 1)))


#: The issue's targets, by row: CPU time [s], peak memory [bytes], energy error, at 10^4 cycles in
#: phase and 10^6 cycles of each.
TARGETS = {
    ("in phase", 10**4): (30.0, None, 1e-4),
    ("in phase", 10**6): (30 * 60.0, 1e9, None),
    ("Q alone", 10**6): (120.0, 1e9, 1e-9),
}


@dataclass
class Row:
    """One row of the table: a run measured (or extrapolated from one, `measured` False)."""

    history: str
    model: str
    cycles: int
    seconds: float
    peak: float | None
    error: float | None
    against: str = ""
    measured: bool = True

    def line(self):
        target = TARGETS.get((self.history, self.cycles))
        peak = "not run" if self.peak is None else f"{self.peak / 1e6:.0f} MB"
        error = "" if self.error is None else f"{self.error:.1e}"
        seconds = f"{self.seconds:.1f} s" if self.measured else f"{self.seconds:.0f} s (extrapolated)"
        met = "" if target is None else _met(target, self)
        return f"| {self.history} | {self.model} | {self.cycles:,} | {seconds} | {peak} | {error} | {met} |"


def _met(target, row):
    """The target of `row` and whether it is met (a part not run or not extrapolated: unknown; an
    extrapolated row, which carries the fixed costs of the shorter run into every cycle: not judged)."""
    if not row.measured:
        return "not judged: extrapolated (--million runs it)"
    limits = [(row.seconds, target[0], f"{target[0]:.0f} s")]
    limits += [(row.peak, target[1], "1 GB")] if target[1] is not None else []
    limits += [(row.error, target[2], f"{target[2]:.0e}")] if target[2] is not None else []
    words = [
        f"{text} {'?' if value is None else ('met' if value <= limit else 'MISSED')}" for value, limit, text in limits
    ]
    return ", ".join(words)


def table(rows):
    """The rows as a Markdown table with the issue's targets, and what each energy error is against."""
    print("| history | model | cycles | CPU | peak memory | energy error | target |")
    print("| --- | --- | ---: | ---: | ---: | ---: | --- |")
    for row in rows:
        print(row.line())
    for row in rows:
        if row.against:
            print(f"- {row.history}, {row.model}, {row.cycles:,} cycles: energy error against {row.against}")


def in_phase_rows(folder, cycles, million):
    """Random in-phase Q and sigma: the default and the fixed grid, each against --every-step; and
    10^6 cycles of the default run if `million`, else extrapolated."""
    rows, prefix = [], min(PREFIX, cycles)
    for options in ((), ("--nodes", str(GRID))):
        output, seconds, peak = run(folder, cycles, True, *options)
        reference = run(folder, prefix, True, *options, "--every-step")[0]
        error = worst(fr.load(output).cycle_dissipation.values[:prefix], fr.load(reference).cycle_dissipation.values)
        against = f"--every-step on the first {prefix} cycles ({_nodes(reference)})"
        history = " ".join(["in phase", *options])  # the targets are the default's: of "in phase" alone
        rows.append(Row(history, _nodes(output), cycles, seconds, peak, error, against))
        fewer = run(folder, cycles // 10, True, *options)
        rows.append(Row(history, _nodes(fewer[0]), cycles // 10, fewer[1], fewer[2], None))
    if million:
        output, seconds, peak = run(folder, 10**6, True)
        rows.append(Row("in phase", _nodes(output), 10**6, seconds, peak, None))
    else:
        rows.append(_extrapolated(rows[0], 10**6))
    return rows


def Q_alone_rows(folder, cycles, million):
    """Random Q alone (the exact model) against the Masing closed form, every cycle; and 10^6 cycles
    run if `million`, else extrapolated."""
    rows = []
    for count in (cycles, cycles // 10, *((10**6,) if million and cycles != 10**6 else ())):
        output, seconds, peak = run(folder, count, False)
        error = worst(fr.load(output).cycle_dissipation.values, masing_energy(output.with_suffix(".toml")))
        rows.append(Row("Q alone", _nodes(output), count, seconds, peak, error, "Masing closed form"))
    if rows[-1].cycles != 10**6:
        rows.append(_extrapolated(rows[0], 10**6))
    return rows


def periodic_rows(folder, million):
    """In-phase sinusoids (their cycles copied): CPU time and peak memory at 10^4 cycles and at 10^6
    if `million`, else 10^5, with the energy of the last cycle against the 10^4 run's."""
    rows, last = [], None
    for count in (10**4, 10**6 if million else 10**5):
        output, seconds, peak = run(folder, count, True, kind="sine")
        energy = fr.load(output).cycle_dissipation.values[-1]
        error = None if last is None else abs(energy / last - 1)
        against = "" if last is None else "the last cycle of the 10^4-cycle run"
        rows.append(Row("sine in phase", _nodes(output), count, seconds, peak, error, against))
        last = energy
    return rows


def out_of_phase_rows(folder):
    """Non-periodic out-of-phase cycles (`out_of_phase_blocks`) at default settings: `OUT_OF_PHASE`
    cycles run, 10^4 extrapolated (every step is solved, on the energy's mesh); the energy per
    cycle of the first `PREFIX_OUT_OF_PHASE` cycles against those cycles run at ``--rtol``
    `FINE_RTOL` (its own change from twice that rtol printed as its convergence)."""
    reference, coarser = (
        run(folder, PREFIX_OUT_OF_PHASE, True, "--rtol", str(rtol), kind="out_of_phase")[0]
        for rtol in (FINE_RTOL, 2 * FINE_RTOL)
    )
    energy = fr.load(reference).cycle_dissipation.values
    converged = worst(fr.load(coarser).cycle_dissipation.values, energy)
    against = f"--rtol {FINE_RTOL:g} on the first {PREFIX_OUT_OF_PHASE} cycles ({_nodes(reference)}; "
    against += f"--rtol {2 * FINE_RTOL:g} differs from it by {converged:.1e})"
    rows = []
    for count in OUT_OF_PHASE:
        output, seconds, peak = run(folder, count, True, kind="out_of_phase")
        error = worst(fr.load(output).cycle_dissipation.values[:PREFIX_OUT_OF_PHASE], energy)
        rows.append(Row("out of phase", _nodes(output), count, seconds, peak, error, against))
    return [*rows, _extrapolated(rows[-1], 10**4)]


def _extrapolated(row, cycles):
    """`row` at `cycles`, its CPU time linear in the cycles; memory and error not known."""
    return Row(row.history, row.model, cycles, row.seconds / row.cycles * cycles, None, None, measured=False)


def main(short=False, Q_only=False, million=False, out_of_phase=False):
    in_phase, Q_alone = (10**3, 10**4) if short else (10**4, 10**5)
    with tempfile.TemporaryDirectory() as directory:
        folder = Path(directory)
        if out_of_phase:
            table(out_of_phase_rows(folder))
            return
        rows = [] if Q_only else in_phase_rows(folder, in_phase, million) + periodic_rows(folder, million)
        table(rows + Q_alone_rows(folder, Q_alone, million))


def _nodes(output):
    """``model, N nodes`` of the result file `output`."""
    attrs = fr.load(output).attrs
    return f"{attrs['model']}, {attrs['nodes']} nodes"


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="10 times fewer cycles: a quick check")
    parser.add_argument("--Q-alone", action="store_true", dest="Q_only", help="the rows of Q alone only")
    parser.add_argument("--million", action="store_true", help="also run 10^6 cycles of each history (minutes)")
    parser.add_argument(
        "--out-of-phase", action="store_true", help="the rows of non-periodic out-of-phase cycles only (minutes)"
    )
    arguments = parser.parse_args()
    main(arguments.short, arguments.Q_only, arguments.million, arguments.out_of_phase)
