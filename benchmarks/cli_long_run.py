"""`fretting run` of 10^5 Hertz cycles: wall time, peak memory, file size and energy per cycle.

The history file is `histories/hertz_shear_cycling.toml`'s contact under one `sine` block of
`Q_amplitude = 35e3` (`Q*/fP = 0.5`), 64 steps per cycle, `cycles = 100000` (6.4 million steps),
run at default settings in a fresh process. Its peak memory is the child's maximum resident
set (`resource.getrusage`); every cycle after the first is compared with the Masing closed
form (`fretting.physics.closed_forms.mindlin_deresiewicz_energy`).

Run:  python benchmarks/cli_long_run.py [CYCLES]   (about 10 s for the default 100000)
"""

import os
import resource
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

import fretting as fr
from fretting.loading.examples import example_path
from fretting.physics.closed_forms import mindlin_deresiewicz_energy

EXAMPLE = example_path("hertz_shear_cycling")
Q_AMPLITUDE = 35e3


def history_text(cycles):
    """The example's contact under `cycles` sine cycles of `Q_AMPLITUDE`, as a history file."""
    contact = tomllib.loads(EXAMPLE.read_text())["contact"]
    lines = ["[contact]", *(f"{key} = {value!r}" for key, value in contact.items())]
    loading = ["[[loading]]", 'kind = "sine"', f"Q_amplitude = {Q_AMPLITUDE}", f"cycles = {cycles}"]
    return "\n".join([*lines, "", *loading, ""])


def main(cycles=100_000):
    with tempfile.TemporaryDirectory() as directory:
        source, output = Path(directory) / "long.toml", Path(directory) / "long.h5"
        source.write_text(history_text(cycles))
        began = time.perf_counter()
        command = [sys.executable, "-m", "fretting", "run", str(source), "-o", str(output)]
        subprocess.run(command, check=True, env=os.environ | {"OPENBLAS_NUM_THREADS": "1"})
        seconds = time.perf_counter() - began
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024  # kB on Linux
        result = fr.load(output)
        contact = fr.read_history(source)[0]
        W = mindlin_deresiewicz_energy(contact, Q_AMPLITUDE)
        error = np.max(np.abs(result.cycle_dissipation.values[1:] / W - 1))
        print(
            f"{cycles} cycles, {result.attrs['steps'] - 1} steps, {result.attrs['nodes']} nodes: "
            f"{seconds:.2f} s wall, peak resident {peak / 1e6:.0f} MB, file {output.stat().st_size / 1e6:.2f} MB, "
            f"energy error {error:.1e} (cycles 2 to {cycles})"
        )


if __name__ == "__main__":
    main(*map(int, sys.argv[1:]))
