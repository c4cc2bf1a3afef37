"""The exact model of in-phase Q and sigma against method 4 on uniform meshes in theta: errors, convergence, time.

The random-amplitude in-phase history of tests/models/test_inphase.py (Hertz, 4 cycles up to 0.8 f P,
``sigma = 0.9 * 4 / (pi a) * Q``, regime A) runs on `fretting.models.InPhase` and on method 4
(``mesh=``) at the same nodes, uniform meshes of 1001 to 4001 angles. Printed, each the largest
over all steps: the traction [f p0] at the nodes farther than 0.01 a from every stick end of the
history and at all nodes, the slip [of the largest slip] at those nodes and at all nodes, the
energy of an increment, delta_Q and delta_sigma [of their largest], the stick ends [a]; and the
CPU time of each run. Where method 4's errors fall with its mesh, the exact model is their limit.

With ``--service-life``: the in-phase history of benchmarks/service_life.py (`CYCLES` random cycles)
through `fretting run` at default settings, its CPU time and peak memory (`service_life.run`), and
the largest relative error of its energy per cycle against method 4 on the finest mesh over the
first `PREFIX` cycles (the same draws): a converged reference, where service_life.py's own row
compares the default with itself solving every step.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/inphase_accuracy.py [--service-life]   (about a minute each)
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
import service_life
from harness import END_BAND, hertz_contact

import fretting as fr
from fretting.models.inphase import InPhase, regime_bound

MESHES = (1001, 2001, 4001)

#: Cycles of the service-life run, and those of its method-4 reference.
CYCLES, PREFIX = 10**4, 8


def history(contact):
    """The test's history: 4 random cycles of Q up to 0.8 f P, 2 steps a segment, sigma in phase."""
    k = 0.9 * regime_bound(contact)
    Q = fr.History.random_amplitude(4, 0.8 * contact.f * contact.P, 0.0, seed=3, steps_per_segment=2).Q
    return fr.History.piecewise_linear(Q, k * Q, 1), k


def timed(contact, loads, **model):
    began = time.process_time()
    return fr.simulate(contact, loads, **model), time.process_time() - began


def errors(contact, exact, reference):
    """The largest differences (module docstring) of the runs `exact` and `reference` at the same nodes."""
    a, fp0 = contact.a, contact.f * contact.p0
    ends = np.concatenate([exact.stick_start.values, exact.stick_end.values], axis=1).ravel() / a
    far = np.abs(exact.x.values[:, None] / a - ends[None, :]).min(axis=1) > END_BAND
    dq = np.abs(exact.q.values - reference.q.values) / fp0
    ds = np.abs(exact.slip.values - reference.slip.values) / np.abs(reference.slip.values).max()
    found = {"q far": dq[:, far].max(), "q all": dq.max(), "slip far": ds[:, far].max(), "slip all": ds.max()}
    for name in ("dissipation", "delta_Q", "delta_sigma"):
        difference = np.abs(exact[name].values - reference[name].values)
        found[name] = difference.max() / np.abs(reference[name].values).max()
    ends = [np.abs(exact[end].values - reference[end].values).max() / a for end in ("stick_start", "stick_end")]
    return found | {"ends": max(ends)}


def main():
    contact = hertz_contact()
    loads, k = history(contact)
    print(f"{len(loads) - 1} steps, sigma/Q = {k:.6g} 1/m (regime A bound {regime_bound(contact):.6g} 1/m)")
    header = None
    for nodes in MESHES:
        theta = np.linspace(0, np.pi, nodes)
        exact, exact_s = timed(contact, loads, model=InPhase(ratio=k, theta=theta))
        reference, reference_s = timed(contact, loads, mesh=theta)
        found = errors(contact, exact, reference)
        if header is None:
            header = ["nodes", *found, "inphase CPU", "method 4 CPU"]
            print("| " + " | ".join(header) + " |")
            print("|" + " ---: |" * len(header))
        cells = [str(nodes), *(f"{value:.2e}" for value in found.values()), f"{exact_s:.2f} s", f"{reference_s:.1f} s"]
        print("| " + " | ".join(cells) + " |")


def service_life_row():
    """The service-life in-phase run at default settings against method 4 on the finest mesh (module docstring)."""
    with tempfile.TemporaryDirectory() as directory:
        folder = Path(directory)
        output, seconds, peak = service_life.run(folder, CYCLES, True)
        source = folder / "prefix.toml"
        source.write_text(service_life.history_text(PREFIX, True))
        reference = fr.simulate(*fr.read_history(source), mesh=np.linspace(0, np.pi, MESHES[-1]))
        result = fr.load(output)
        error = service_life.worst(result.cycle_dissipation.values[:PREFIX], reference.cycle_dissipation.values)
        print(
            f"in phase, {CYCLES:,} cycles, default ({result.attrs['model']}, {result.attrs['nodes']} nodes): "
            f"{seconds:.1f} s CPU, {peak / 1e6:.0f} MB; energy per cycle against method 4 on {MESHES[-1]} "
            f"nodes over the first {PREFIX} cycles: {error:.1e}"
        )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--service-life", action="store_true", help="the service-life in-phase row instead")
    if parser.parse_args().service_life:
        service_life_row()
    else:
        main()
