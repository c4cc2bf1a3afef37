"""Cost of tallying the per-cycle peaks of the specimen's surface stress at every step.

A 1000-step default run with sigma that solves every step (10 cycles of 100 steps, Q and sigma 90
degrees out of phase, each cycle's amplitudes 1 % above the last, so that no cycle is copied):
the CPU time of `fretting.simulate` (best of `--repeats`, the mesh adaptation included), and of
the tally's own work per step (`fretting.engine.follow.specimen_surface`: the model's traction
and one product with the precomputed Hilbert matrix) on the run's nodes, with its share of the run.

    python benchmarks/cycle_peaks.py [--repeats 5]
"""

import argparse
import time

import fretting as fr
from fretting.engine.follow import advance, specimen_surface
from fretting.engine.threads import one_blas_thread
from fretting.loading.loads import Loads

CONTACT = fr.Contact(fr.Hertz(0.05), 115.38e9, 0.7, 1e5)


def history():
    fP = CONTACT.f * CONTACT.P
    base = fr.History.sinusoidal(0.5 * fP, 100e6, cycles=10, steps_per_cycle=100, phase_deg=90)
    scale = 1.01**base.cycle
    return fr.History(base.Q * scale, base.sigma * scale, base.vertex_step, base.cycle)


def best(run, repeats):
    times = []
    for _ in range(repeats):
        start = time.process_time()
        run()
        times.append(time.process_time() - start)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    repeats = parser.parse_args().repeats
    loads = history()
    result = fr.simulate(CONTACT, loads)
    run = best(lambda: fr.simulate(CONTACT, loads), repeats)
    stepper = fr.Stepper(CONTACT)
    stepper.resolve(loads)
    model = stepper.model
    sigma = 50e6
    outcome, _ = advance(model, stepper.state, Loads(0.3 * CONTACT.f * CONTACT.P, sigma))
    calls = 1000
    with one_blas_thread():
        specimen_surface(model, outcome, sigma)  # builds the matrix once per model

        def tally():
            for _ in range(calls):
                specimen_surface(model, outcome, sigma)

        per_step = best(tally, repeats) / calls
    steps, copied = len(loads) - 1, int(result.cycle_copied.sum())
    print(
        f"{steps} steps, {copied} copied cycles, {model.x.size} nodes ({result.attrs['model']}):"
        f" simulate {run:.3f} s CPU; tally {per_step * 1e6:.1f} us per step, {steps * per_step:.3f} s"
        f" ({steps * per_step / run:.1%} of the run)"
    )


if __name__ == "__main__":
    main()
