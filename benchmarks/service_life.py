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

- spectra (``--spectra`` alone, issue 34): non-periodic out-of-phase spectra (`spectrum`: every
  cycle its own random amplitudes of Q and sigma and its own phase between them, `SPECTRUM_STEPS`
  steps a cycle), with a constant normal load and with a varying one (each cycle its own amplitude
  and phase of P), run by ``fretting.simulate`` at default settings recording the last step, in a
  fresh process each, for the cycles of `SPECTRUM_CYCLES`; the time and memory of 10^4 and 10^6
  cycles projected from the last two (linear in the cycles beyond the longest run, at the cost per
  cycle between the last two: the mesh of the default, and what the models keep of the contacts
  they meet, have reached their bounds by the second); the energy per cycle of
  the first cycles against `dense_method4` on a converged grid (its change from a coarser grid
  printed); and the CPU time per step of the varying load over that of the constant load on the
  same history, with the default of each and with `fretting.models.Varying` on both.

The table ends each row with the issue's target and whether it is met ("?" where the row does not
give that figure).

CPU time is the child's user + system time and peak memory its maximum resident set
(`resource.getrusage` of a wrapper process that runs only that child). Cycles beyond those run
are extrapolated linearly in the cycles, and printed as such.

Run:  python benchmarks/service_life.py [--short] [--Q-alone] [--million] [--out-of-phase]   (--short:
10^3 cycles in phase and 10^4 of Q alone, two minutes; default 10^4 and 10^5, about 15 minutes;
--Q-alone: the rows of Q alone only; --million: 10^6 cycles of each as well, half an hour more;
--out-of-phase: those rows only, ten minutes; --spectra: the spectra of issue 34 only, ten minutes)
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


#: Spectra of issue 34: cycles of the three timed runs (the energy error of the first, the cost per cycle
#: between the last two), steps a cycle, largest relative amplitude of P.
SPECTRUM_CYCLES, SPECTRUM_STEPS, P_AMPLITUDE = (8, 24, 72), 32, 0.1

#: Grids of `dense_method4` for the spectra's reference energies (the first of `SPECTRUM_CYCLES`
#: cycles): the reference and the coarser one it is checked against; and its parts where P varies.
SPECTRUM_NODES = {False: (2048, 1536), True: (1024, 768)}
SPECTRUM_LOAD_PART = 1 / 1600

#: The targets of issue 34 for the spectra: CPU time [s] and peak memory [bytes] by cycles, and the
#: largest ratio of the CPU time per step of a varying normal load over that of a constant one.
SPECTRUM_TARGETS = {10**4: (60.0, None), 10**6: (2 * 3600.0, 1e9)}
VARYING_P_RATIO = 2.0

#: A child that runs a spectrum at default settings (``varying_P``; ``same_cells``: on
#: `fretting.models.Varying`) recording the last step and prints its CPU time, peak memory and
#: energy per cycle.
SPECTRUM_CHILD = """
import json, resource, sys, time
sys.path.insert(0, {here!r})
import fretting as fr
import service_life
from fretting.models.normal import Varying
spec = json.loads(sys.argv[1])
contact, history = service_life.spectrum(spec["cycles"], spec["varying_P"])
model = {{"model": Varying()}} if spec["same_cells"] else {{}}
start = time.process_time()
result = fr.simulate(contact, history, record=[len(history) - 1], **model)
cpu = time.process_time() - start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({{"cpu": cpu, "peak": peak, "energy": result.cycle_dissipation.values.tolist(),
                  "model": f"{{result.attrs['model']}}, {{result.attrs['nodes']}} nodes"}}))
"""


def spectrum(cycles, varying_P=False, seed=SEED):
    """The example's contact and `cycles` non-periodic out-of-phase cycles of `SPECTRUM_STEPS` steps.

    Cycle ``k``: ``Q = Q_AMPLITUDE A_k sin(theta)``, ``sigma = SIGMA_AMPLITUDE B_k sin(theta +
    phi_k)``, ``theta = 2 pi j / SPECTRUM_STEPS``, ``j = 1 .. SPECTRUM_STEPS``, with ``A_k``,
    ``B_k`` uniform in [0.5, 1) and ``phi_k`` in [45, 135) degrees; with `varying_P`, ``P = P_0 (1
    + C_k (sin(theta + psi_k) - sin(psi_k)))``, ``C_k`` uniform in [0, `P_AMPLITUDE`), ``psi_k`` in
    [0, 360) degrees: every cycle starts and ends at ``P_0``, ``Q = 0``. Seeded draws
    (`numpy.random.default_rng`), the first cycles the same whatever `cycles`; the loads are
    straight between the steps.
    """
    contact = fr.read_history(EXAMPLE)[0]
    rng = np.random.default_rng(seed)
    A, B, phi, C, psi = np.moveaxis(rng.random((cycles, 5, 1)), 1, 0)  # a row a cycle: the first cycles stay
    theta = 2 * np.pi * np.arange(1, SPECTRUM_STEPS + 1) / SPECTRUM_STEPS
    Q = Q_AMPLITUDE * (0.5 + A / 2) * np.sin(theta)
    sigma = SIGMA_AMPLITUDE * (0.5 + B / 2) * np.sin(theta + np.radians(45 + 90 * phi))
    P = None
    if varying_P:
        psi = 2 * np.pi * psi
        P = np.concatenate(
            [[contact.P], (contact.P * (1 + P_AMPLITUDE * C * (np.sin(theta + psi) - np.sin(psi)))).ravel()]
        )
    cycle = np.concatenate([[0], np.repeat(np.arange(1, cycles + 1), SPECTRUM_STEPS)])
    loads = (np.concatenate([[0.0], v.ravel()]) for v in (Q, sigma))
    return contact, fr.History(*loads, np.arange(0, cycles * SPECTRUM_STEPS + 1, SPECTRUM_STEPS), cycle, P)


def spectrum_run(cycles, varying_P, same_cells=False):
    """What `SPECTRUM_CHILD` prints for `cycles` cycles: ``cpu`` [s], ``peak`` [bytes], ``energy`` [J/m]
    per cycle and ``model``."""
    spec = json.dumps({"cycles": cycles, "varying_P": varying_P, "same_cells": same_cells})
    code = SPECTRUM_CHILD.format(here=str(Path(__file__).resolve().parent))
    found = subprocess.run(
        [sys.executable, "-c", code, spec], check=True, capture_output=True, text=True, env=os.environ | ONE_THREAD
    )
    return json.loads(found.stdout.splitlines()[-1])


def spectrum_reference(varying_P):
    """Energy per cycle [J/m] of the first ``SPECTRUM_CYCLES[0]`` cycles by `dense_method4` on the
    finer of `SPECTRUM_NODES`, and the largest relative change from the coarser."""
    import dense_method4

    contact, history = spectrum(SPECTRUM_CYCLES[0], varying_P)
    energies = [
        np.bincount(history.cycle, weights=dense_method4.simulate(contact, history, n, SPECTRUM_LOAD_PART).dissipation)[
            1:
        ]
        for n in SPECTRUM_NODES[varying_P]
    ]
    return energies[0], worst(energies[1], energies[0])


def spectra_rows():
    """The spectra of issue 34: a table of the constant and the varying normal load, each at its
    default, with projected time and memory and the energy error of the first cycles; then the
    ratios of the CPU time per step, varying over constant."""
    few, middle, many = SPECTRUM_CYCLES
    print("| spectrum | model | cycles run | CPU s | peak MB | energy error | 10^4 cycles | 10^6 cycles | target |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    per_step, notes = {}, []
    for varying_P in (False, True):
        name = "out of phase, varying P" if varying_P else "out of phase"
        short, between, long = runs = [spectrum_run(n, varying_P) for n in SPECTRUM_CYCLES]
        reference, change = spectrum_reference(varying_P)
        error = worst(np.array(short["energy"]), reference)
        fine, coarse = SPECTRUM_NODES[varying_P]
        notes.append(f"- {name}: energy per cycle of the first {few} cycles against dense_method4 N = {fine}"
                     f" (N = {coarse} differs from it by {change:.1e})")  # fmt: skip
        cpu_cycle = (long["cpu"] - between["cpu"]) / (many - middle)
        peak_cycle = max(long["peak"] - between["peak"], _loads_bytes(varying_P)) / (many - middle)
        per_step[varying_P] = cpu_cycle / SPECTRUM_STEPS
        projected = {
            n: (long["cpu"] + cpu_cycle * (n - many), long["peak"] + peak_cycle * (n - many)) for n in SPECTRUM_TARGETS
        }
        cells = [f"{seconds:.0f} s, {peak / 1e9:.2g} GB" for seconds, peak in projected.values()]
        cpu, peak = (", ".join(f"{r[key] / scale:.{digits}f}" for r in runs) for key, scale, digits in
                     (("cpu", 1, 1), ("peak", 1e6, 0)))  # fmt: skip
        print(f"| {name} | {long['model']} | {few}, {middle}, {many} | {cpu} | {peak} | {error:.1e} | "
              f"{' | '.join(cells)} | {_spectrum_met(projected)} |")  # fmt: skip
    same = {
        v: spectrum_run(many, v, same_cells=True)["cpu"] - spectrum_run(middle, v, same_cells=True)["cpu"]
        for v in (False, True)
    }
    for line in notes:
        print(line)
    print(
        "- projected: the longest run plus the cost per cycle between the last two runs (CPU time; peak memory, at"
        " least the loads of the history held by its steps, 8 bytes a load and 4 a cycle number: an upper bound where"
        " the records and the fields per cycle stop growing)"
    )
    for label, ratio in (
        ("the default of each", per_step[True] / per_step[False]),
        ("fretting.models.Varying on both (the same cells)", same[True] / same[False]),
    ):
        met = "met" if ratio <= VARYING_P_RATIO else "MISSED"
        print(
            f"- CPU time per step, varying P over constant P on the same history, {label}: {ratio:.2f}"
            f" (target <= {VARYING_P_RATIO:g}: {met})"
        )


def _loads_bytes(varying_P):
    """Bytes [B] of the loads of the cycles between the last two `SPECTRUM_CYCLES` held by their steps (`spectrum`'s
    arrays)."""
    middle, many = SPECTRUM_CYCLES[1:]
    history = spectrum(many - middle, varying_P)[1]
    return sum(v.nbytes for v in (history.Q, history.sigma, history.cycle, history.P) if v is not None)


def _spectrum_met(projected):
    words = []
    for cycles, (seconds, memory) in SPECTRUM_TARGETS.items():
        at_seconds, at_peak = projected[cycles]
        words.append(f"10^{round(np.log10(cycles))}: < {seconds:.0f} s {'met' if at_seconds <= seconds else 'MISSED'}")
        if memory is not None:
            words.append(f"< {memory / 1e9:g} GB {'met' if at_peak <= memory else 'MISSED (upper bound)'}")
    return ", ".join(words)


def main(short=False, Q_only=False, million=False, out_of_phase=False, spectra=False):
    in_phase, Q_alone = (10**3, 10**4) if short else (10**4, 10**5)
    if spectra:
        spectra_rows()
        return
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
    parser.add_argument(
        "--spectra", action="store_true", help="the non-periodic spectra of issue 34 only, constant and varying P"
    )
    arguments = parser.parse_args()
    main(arguments.short, arguments.Q_only, arguments.million, arguments.out_of_phase, arguments.spectra)
