"""Ctrl-C at random times in `fretting run` (issue 38): what each interrupt printed, and whether the
run resumed to the uninterrupted result.

Each try starts ``python -m fretting run EXAMPLE`` in a fresh folder, sends SIGINT after a random
delay drawn between the process's start and the uninterrupted run's duration, and then completes
the run (``--resume`` where a checkpoint was kept). A try is clean when the interrupted process
exited 130 with one line on stderr (or 0, having finished before the signal arrived, with nothing on
stderr), and the completed result equals the uninterrupted one. Prints one row a try and the count of
clean tries; exits 1 if any try was not clean. An interrupt while Python imports fretting and its
dependencies, before `fretting.cli.main` runs, gets Python's own traceback ("start-up traceback"):
nothing is written by then.

    python benchmarks/interrupts.py [--tries 12] [--example hertz_shear_cycling] [--seed 0] [--verbose]
"""

import argparse
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from fretting.results.io import WRITTEN_ATTRIBUTES, load


def command(example, output, *options):
    return [sys.executable, "-m", "fretting", "run", example, "-o", output, "--checkpoint-interval", "0", *options]


def data_of(result):
    """`result` without what differs between two writes of it."""
    copy = result.drop_vars("cycle_copied", errors="ignore")
    copy.attrs = {name: value for name, value in result.attrs.items() if name not in WRITTEN_ATTRIBUTES}
    return copy


def one_try(example, folder, delay, whole):
    """Interrupt a run after `delay` seconds, complete it; (code, stderr, clean)."""
    process = subprocess.Popen(command(example, "out.h5"), cwd=folder, stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=300)
    code = process.returncode
    said = code == 130 and err.count("\n") == 1 and err.startswith("fretting: error: interrupted")
    finished = code == 0 and err == ""
    resume = ["--resume"] if (Path(folder) / "out.h5.checkpoint").is_dir() else []
    if not finished:
        done = subprocess.run(command(example, "out.h5", *resume), cwd=folder, capture_output=True, text=True)
        if done.returncode:
            return code, err + done.stderr, False
    same = data_of(load(Path(folder) / "out.h5")).identical(data_of(whole))
    return code, err, (said or finished) and same


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tries", type=int, default=12)
    parser.add_argument("--example", default="hertz_shear_cycling")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--verbose", action="store_true", help="print the stderr of each try that is not clean")
    args = parser.parse_args(argv)
    draw = random.Random(args.seed)
    with tempfile.TemporaryDirectory() as reference:
        began = time.monotonic()
        subprocess.run(command(args.example, "whole.h5"), cwd=reference, check=True, capture_output=True)
        duration = time.monotonic() - began
        whole = load(Path(reference) / "whole.h5")
    print(f"{args.example}: uninterrupted run {duration:.2f} s; SIGINT at a uniform time in [0, {duration:.2f}] s")
    clean = 0
    for number in range(args.tries):
        delay = draw.uniform(0, duration)
        with tempfile.TemporaryDirectory() as folder:
            code, err, ok = one_try(args.example, folder, delay, whole)
        clean += ok
        first = err.strip().splitlines()[:1] or [""]
        kind = "ignored exception" if "Exception ignored" in err else "traceback" if "Traceback" in err else ""
        kind = "start-up traceback" if kind == "traceback" and "fretting/cli/" not in err else kind
        print(
            f"{number:3d} {delay:6.3f} s exit {code:4d} {'clean' if ok else 'NOT CLEAN':9} {kind:18} {first[0][:100]}"
        )
        if not ok and args.verbose:
            print("    " + err.strip().replace("\n", "\n    "))
    print(f"{clean} of {args.tries} tries clean")
    return 0 if clean == args.tries else 1


if __name__ == "__main__":
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    sys.exit(main())
