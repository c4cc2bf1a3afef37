"""The default run with BLAS on one thread (as the engine runs it) and on two.

The stepper and the mesh adaptation limit BLAS and LAPACK to
`fretting.engine.threads.BLAS_THREADS` threads while they run. This script times the default run of
the harness's 10-vertex random scene (Hertz, 8 steps per segment, 72 steps) as it is, and
unwrapped under two threads (`threadpoolctl`), and prints the wall time per step (fastest of 3).

Run:  python benchmarks/blas_threads.py   (about 20 seconds on a 2-core machine)
"""

import sys
import time

import harness
from threadpoolctl import threadpool_limits

import fretting as fr
from fretting.engine import threads


def ms_per_step(run, contact, history):
    """Fastest of 3 wall times of `run` [ms per step]."""
    run(contact, history)
    times = []
    for _ in range(3):
        start = time.perf_counter()
        run(contact, history)
        times.append(time.perf_counter() - start)
    return min(times) / (len(history) - 1) * 1e3


def main():
    contact = harness.hertz_contact()
    history = harness.baseline_history(contact, 8)
    print(
        f"engine (BLAS_THREADS = {threads.BLAS_THREADS}): {ms_per_step(fr.simulate, contact, history):.2f} ms per step"
    )
    with threadpool_limits(limits=2, user_api="blas"):
        limit = threads.one_blas_thread
        threads_kept = lambda: threadpool_limits(limits=2, user_api="blas")  # noqa: E731
        for module in (sys.modules["fretting.engine.stepper"], sys.modules["fretting.engine.simulation"]):
            module.one_blas_thread = threads_kept  # without the engine's limit
        try:
            print(f"BLAS on 2 threads: {ms_per_step(fr.simulate, contact, history):.2f} ms per step")
        finally:
            for module in (sys.modules["fretting.engine.stepper"], sys.modules["fretting.engine.simulation"]):
                module.one_blas_thread = limit


if __name__ == "__main__":
    main()
