"""Cost of the default model on random out-of-phase cycles, where Galerkin meshes grow largest.

Draws scenes from the families of `harness.SHAPES` (Hertz, rounded flat and asymmetric flat
profiles; f, P, and Q, sigma amplitudes and phase as tests/test_hard_properties.py's
`test_loop_work_equals_dissipation_on_non_proportional_cycles` draws them), runs 30 cycles of
32 steps at default settings and prints the model each got and the wall time: the default
gives up a mesh of more than `fretting.MAX_DEFAULT_MESH` nodes for the grid.

Run:  python benchmarks/default_out_of_phase.py [SEED] [SCENES]   (defaults 1 and 40; about 2 minutes)
"""

import sys
import time

import numpy as np
from harness import SHAPES, SMOOTH, family_contact

import fretting as fr


def main(seed=1, scenes=40):
    rng = np.random.default_rng(seed)
    times = []
    for _ in range(scenes):
        kind = str(rng.choice(SMOOTH))
        shape = SHAPES[kind][rng.integers(len(SHAPES[kind]))]
        scene = family_contact(kind, tuple(shape), float(rng.choice([0.3, 0.6, 1.0])), float(rng.choice([3e4, 3e5])))
        psi, tau, phase = rng.uniform(0.1, 0.7), rng.uniform(0.1, 1.5), rng.uniform(30, 150)
        history = fr.History.sinusoidal(
            psi * scene.f * scene.P, tau * scene.f * scene.p0, phase, cycles=30, steps_per_cycle=32
        )
        began = time.perf_counter()
        result = fr.simulate(scene, history, record=[0])
        times.append(time.perf_counter() - began)
        model = f"rtol {result.attrs['rtol']:g}" if "rtol" in result.attrs else "grid"
        print(
            f"{kind:12} Q {psi:.2f} fP, sigma {tau:.2f} f p0, {phase:5.1f} deg: "
            f"{model:10} {result.attrs['nodes']:5d} nodes {times[-1]:6.2f} s",
            flush=True,
        )
    print(f"{scenes} scenes: median {np.median(times):.2f} s, max {max(times):.2f} s")


if __name__ == "__main__":
    main(*map(int, sys.argv[1:]))
