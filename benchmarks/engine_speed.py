"""CPU time of `fretting.simulate` on four scenes, the default and the 384-node grid.

Hertz (R = 50 mm, E* = 115 GPa, f = 0.6, P = 1e5 N/m): a 10-vertex random walk of Q and sigma
(16 steps per segment) with the default (mesh adaptation included) and with ``nodes=384``; the
same walk of Q alone (the default: the exact model); 20 cycles of Q and sigma 90 degrees out of
phase (32 steps per cycle, the default). Least CPU time of `--repeats` runs, one BLAS thread.
It uses only ``fretting.simulate(contact, history[, nodes=])``, so an older checkout runs it
too (``PYTHONPATH=<checkout> python benchmarks/engine_speed.py``) for a before/after figure.

    python benchmarks/engine_speed.py [--repeats 3]
"""

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import fretting as fr  # noqa: E402

CONTACT = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e5)


def walks():
    """The 10-vertex random walk of Q and sigma (16 steps per segment) and the same walk of Q alone."""
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    rng = np.random.default_rng(0)
    Q = np.concatenate([[0.0], rng.uniform(-0.7, 0.7, 10)]) * fP
    sigma = np.concatenate([[0.0], rng.uniform(-0.7, 0.7, 10)]) * fp0
    return fr.History.piecewise_linear(Q, sigma, 16), fr.History.piecewise_linear(Q, None, 16)


def scenes():
    """(label, history, keywords of simulate)."""
    fP, fp0 = CONTACT.f * CONTACT.P, CONTACT.f * CONTACT.p0
    walk, shear = walks()
    out_of_phase = fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, 90, cycles=20, steps_per_cycle=32)
    return [
        ("Q/sigma walk, default", walk, {}),
        ("Q/sigma walk, grid 384", walk, {"nodes": 384}),
        ("Q walk, default (exact model)", shear, {}),
        ("20 out-of-phase cycles, default", out_of_phase, {}),
    ]


def cpu(compute, repeats):
    """Least CPU time [s] of `repeats` calls of `compute`, and its last value."""
    best = np.inf
    for _ in range(repeats):
        start = time.process_time()
        value = compute()
        best = min(best, time.process_time() - start)
    return best, value


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"fretting {fr.__version__} from {os.path.dirname(fr.__file__)}")
    for label, history, keywords in scenes():
        best, _ = cpu(lambda h=history, k=keywords: fr.simulate(CONTACT, h, **k), args.repeats)
        print(f"{label:<34} {len(history):>5} steps {best:8.3f} s")


if __name__ == "__main__":
    main()
