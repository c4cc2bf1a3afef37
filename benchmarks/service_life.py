"""Service lives through `fretting run`: CPU time, peak memory and energy error of long random histories.

The targets of issue 21, on the contact of `fretting/examples/hertz_shear_cycling.toml` under a
`random` block (16 steps a segment, 32 a cycle, seed 1; ``Q_amplitude = 40e3``, 0.57 f P, and,
in phase, ``sigma_amplitude = 1e8``, 0.53 f p0), each run at default settings by `fretting run`
in a fresh process, on one BLAS thread:

- random in-phase Q and sigma, the default model: energy per cycle against a run solving every
  step (``--every-step``) of the first `PREFIX` cycles (a prefix of the same draws; the default
  adapts its mesh to that history, so the two runs differ by their meshes as well);
- the same on the fixed grid of `GRID` nodes, against ``--every-step`` on that grid: the cost
  of the steps alone and the error of skipping them;
- random Q alone, the default (the exact model): energy per cycle against the Masing walk of
  the Mindlin-Deresiewicz closed form over every cycle (`masing_energy`);
- peak memory of each at 10 times fewer cycles, to show that it does not grow with the cycles
  (histories past 625 cycles record the same 8192 steps).

CPU time is the child's user + system time and peak memory its maximum resident set
(`resource.getrusage` of a wrapper process that runs only that child). Cycles beyond those run
are extrapolated linearly in the cycles, and printed as such.

Run:  python benchmarks/service_life.py [--short]   (--short: 10^3 cycles in phase and 10^4 of Q
alone, two minutes; default 10^4 and 10^5, about 15 minutes)
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

import numpy as np

import fretting as fr
from fretting.physics.closed_forms import cattaneo_mindlin_dissipation, masing_increment

EXAMPLE = Path(__file__).resolve().parents[1] / "fretting" / "examples" / "hertz_shear_cycling.toml"
Q_AMPLITUDE, SIGMA_AMPLITUDE, STEPS_PER_SEGMENT, SEED = 40e3, 1e8, 16, 1

#: Nodes of the fixed grid run beside the default (that of its fallback): the cost of the steps
#: alone, without the default's mesh adaptation.
GRID = 384

#: Cycles of the reference run that solves every step: a prefix of the same draws.
PREFIX = 200

#: A child that runs `fretting run` with the arguments given and prints its CPU time and peak memory.
WRAPPER = """
import json, resource, subprocess, sys
subprocess.run([sys.executable, "-m", "fretting", "run", *sys.argv[1:]], check=True, stdout=subprocess.DEVNULL)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"cpu": usage.ru_utime + usage.ru_stime, "peak": usage.ru_maxrss * 1024}))
"""

ONE_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}


def history_text(cycles, sigma):
    """The example's contact under `cycles` random cycles (with bulk tension if `sigma`), as a history file."""
    contact = tomllib.loads(EXAMPLE.read_text())["contact"]
    lines = ["[contact]", *(f"{key} = {value!r}" for key, value in contact.items()), "", "[[loading]]"]
    lines += ['kind = "random"', f"cycles = {cycles}", f"Q_amplitude = {Q_AMPLITUDE}", f"seed = {SEED}"]
    lines += [f"steps_per_segment = {STEPS_PER_SEGMENT}"] + ([f"sigma_amplitude = {SIGMA_AMPLITUDE}"] if sigma else [])
    return "\n".join([*lines, ""])


def run(folder, cycles, sigma, *options):
    """``(result file, cpu seconds, peak bytes)`` of `fretting run` on `cycles` random cycles."""
    source = folder / f"{'in_phase' if sigma else 'Q_alone'}_{cycles}{'_'.join(['', *options])}.toml"
    source.write_text(history_text(cycles, sigma))
    output = source.with_suffix(".h5")
    command = [sys.executable, "-c", WRAPPER, str(source), "-o", str(output), *options]
    found = subprocess.run(command, check=True, capture_output=True, text=True, env=os.environ | ONE_THREAD)
    usage = json.loads(found.stdout)
    return output, usage["cpu"], usage["peak"]


def masing_energy(source):
    """Energy [J/m] of each cycle of the Q-alone history file `source` from closed forms: the
    Masing walk of its vertices (`masing_increment`), each branch piece dissipating ``k (E(|Q_end -
    origin| / k) - E(|Q_start - origin| / k))`` with ``E`` the Cattaneo-Mindlin energy of
    monotonic loading (`cattaneo_mindlin_dissipation`) and ``k`` the branch's factor."""
    contact, history = fr.read_history(source)
    energy = np.zeros(history.cycle_count + 1)
    turning, before = (), 0.0
    for step in history.vertex_step[1:]:
        Q = float(history.Q[step])
        turning, pieces = masing_increment(turning, before, Q)
        for origin, factor, start, end in pieces:
            virgin = (cattaneo_mindlin_dissipation(contact, abs(load - origin) / factor) for load in (end, start))
            energy[history.cycle[step]] += factor * (next(virgin) - next(virgin))
        before = Q
    return energy[1:]


def worst(energy, reference):
    """Largest relative error of the energies per cycle."""
    return float(np.max(np.abs(energy / reference - 1)))


def report(label, cycles, seconds, peak, error, against):
    """One line of the table."""
    print(f"{label:<34} {cycles:>9,} cycles  {seconds:8.1f} s CPU  {peak / 1e6:6.0f} MB  ", end="")
    print(f"energy error {error:.1e} ({against})")


def main(short=False):
    in_phase, Q_alone = (10**3, 10**4) if short else (10**4, 10**5)
    with tempfile.TemporaryDirectory() as directory:
        folder = Path(directory)
        output, seconds, peak = run(folder, in_phase, True)
        result = fr.load(output)
        prefix = min(PREFIX, in_phase)
        reference = fr.load(run(folder, prefix, True, "--every-step")[0])
        error = worst(result.cycle_dissipation.values[:prefix], reference.cycle_dissipation.values)
        model = f"{result.attrs['model']}, {result.attrs['nodes']} nodes"
        against = (
            f"--every-step on the first {prefix} cycles: {reference.attrs['model']}, {reference.attrs['nodes']} nodes"
        )
        report(f"in-phase Q and sigma ({model})", in_phase, seconds, peak, error, against)
        print(f"  -> 10^4 cycles: {seconds / in_phase * 1e4:.0f} s (target 30 s, energy within 1e-4)")
        print(f"  -> 10^6 cycles: {seconds / in_phase * 1e6 / 60:.0f} min, extrapolated (target 30 min, 1 GB)")
        fewer = run(folder, in_phase // 10, True)
        print(f"  peak memory at {in_phase // 10:,} cycles: {fewer[2] / 1e6:.0f} MB ({_nodes(fewer[0])})")

        output, seconds, peak = run(folder, in_phase, True, "--nodes", str(GRID))
        reference = run(folder, prefix, True, "--nodes", str(GRID), "--every-step")[0]
        error = worst(fr.load(output).cycle_dissipation.values[:prefix], fr.load(reference).cycle_dissipation.values)
        against = f"--every-step on the first {prefix} cycles, same grid"
        report(f"in-phase Q and sigma (--nodes {GRID})", in_phase, seconds, peak, error, against)
        fewer = run(folder, in_phase // 10, True, "--nodes", str(GRID))
        print(f"  peak memory at {in_phase // 10:,} cycles: {fewer[2] / 1e6:.0f} MB")

        output, seconds, peak = run(folder, Q_alone, False)
        result = fr.load(output)
        error = worst(result.cycle_dissipation.values, masing_energy(output.with_suffix(".toml")))
        report(f"Q alone ({result.attrs['model']})", Q_alone, seconds, peak, error, "Masing closed form, every cycle")
        print(f"  -> 10^6 cycles: {seconds / Q_alone * 1e6 / 60:.1f} min, extrapolated (target 2 min, 1 GB, 1e-9)")
        fewer = run(folder, Q_alone // 10, False)
        print(f"  peak memory at {Q_alone // 10:,} cycles: {fewer[2] / 1e6:.0f} MB ({_nodes(fewer[0])})")


def _nodes(output):
    """``model, N nodes`` of the result file `output`."""
    attrs = fr.load(output).attrs
    return f"{attrs['model']}, {attrs['nodes']} nodes"


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="10 times fewer cycles: a quick check")
    main(parser.parse_args().short)
