"""The guide page docs/guide/displacement.md: displacement control, gross slip, fretting loops and a
running-condition map.

Imported by scripts/make_validation.py (``--only displacement``), which stamps and writes the page and its
figures. It runs the shipped example hertz_fretting_wear_gross_slip (partial slip, gross slip, partial slip
again), reduces its loops (`fretting.studies.running.loop_cycles`), and maps the regime and the energy per
cycle of its contact over `LOADS` x `AMPLITUDES` (`fretting.studies.running.running_map`).
"""

import time

import matplotlib.pyplot as plt
import numpy as np

import fretting as fr
from fretting import plots
from fretting.loading.examples import example_path
from fretting.results.variables import REGIMES
from fretting.studies import running

#: The shipped example the page runs.
EXAMPLE = "hertz_fretting_wear_gross_slip"
#: Normal loads [N/m] and displacement amplitudes [m] of the map.
LOADS = np.array([2.5e4, 5e4, 7.5e4, 1e5, 1.5e5, 2e5])
AMPLITUDES = np.array([0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0]) * 1e-6
#: Cycles per point of the map (the last one is kept) and steps per quarter cycle.
CYCLES, STEPS = 2, 16


def body(table, save_figure):
    """The page's text below its stamp; ``table(header, rows)`` writes a markdown table, ``save_figure(fig,
    name)`` saves a figure into docs/validation/figures."""
    contact, history = fr.read_history(example_path(EXAMPLE))
    began = time.perf_counter()
    result = fr.simulate(contact, history)
    loops = running.loop_cycles(result)
    run_seconds = time.perf_counter() - began
    delta_t = running.transition_displacement(contact)
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    plots.fretting_loops(result, cycles=[1, 4, 7], ax=ax)
    save_figure(fig, "displacement_loops.png")

    began = time.perf_counter()
    mapped = running.running_map(contact, LOADS, AMPLITUDES, cycles=CYCLES, steps=STEPS)
    map_seconds = time.perf_counter() - began
    fig, axes = plt.subplots(1, 2, figsize=(12.8, 4.8))
    plots.running_condition_map(mapped, "cycle_regime", ax=axes[0])
    plots.running_condition_map(mapped, "energy_ratio", ax=axes[1])
    save_figure(fig, "running_map.png")

    def number(value, digits=4):
        return "-" if np.isnan(value) else f"{value:.{digits}g}"

    cycle_rows = [
        [
            str(int(n)),
            number(float(loops.Q_amplitude.sel(cycle_number=n)) / (contact.f * contact.P)),
            number(float(loops.delta_amplitude.sel(cycle_number=n)) * 1e6),
            number(float(loops.loop_opening.sel(cycle_number=n)) * 1e6),
            number(float(loops.cycle_dissipation.sel(cycle_number=n)) * 1e3),
            number(float(loops.energy_ratio.sel(cycle_number=n)), 3),
            number(float(loops.sliding_ratio.sel(cycle_number=n)), 3),
            REGIMES[int(loops.cycle_regime.sel(cycle_number=n))].replace("_", " "),
        ]
        for n in loops.cycle_number.values
    ]
    boundary_rows = [
        [f"{P / 1e3:g}", f"{boundary * 1e6:.4g}", f"{contact.f * P / 1e3:.4g}"]
        for P, boundary in zip(LOADS, mapped.transition.values, strict=True)
    ]
    return f"""
A fretting-wear rig, and many fretting-fatigue rigs, impose the tangential *displacement* of the pad
relative to the specimen rather than the shear force `Q`, and record the fretting loop, `Q` against
that displacement, cycle by cycle. `fretting` follows such a history: each step finds the `Q` that
meets the displacement `delta` with the contact's memory carried exactly, and where `delta` goes beyond
what `Q` below `f P` can reach, the whole contact slides (gross slip) and sticks again on reversal.
The theory, with the closed forms the tests check, is on [Displacement control](../theory/displacement.md).

## The datum

In plane strain the displacement of a half-plane under a net shear force is defined only relative to a
chosen point: the contact takes the distance `L` from its middle at which `delta` is measured, and
optionally the compliance `C` of the rig in series ([why](../theory/displacement.md#datum)):

```python
import fretting as fr

contact = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), f=0.7, P=1e5, datum=5e-3)
history = fr.History.piecewise_linear(delta=[0, 3e-6, -3e-6, 3e-6], steps_per_segment=64)
result = fr.simulate(contact, history)   # the exact model of Q alone: it follows gross slip
result.Q, result.delta, result.regime    # per step; regime 0 stuck, 1 partial slip, 2 gross slip
```

In a history file, `datum` (and `compliance`) are keys of `[contact]`, and `delta` replaces `Q` in a
`linear` block. A history gives either `Q` or `delta` at each step; a `delta` without a datum, a
negative or too short datum, and `Q` and `delta` in one block are one-line errors naming the file and
the key.

## Gross slip

When `|Q|` reaches `f P` under displacement control the contact slides whole by whatever `delta` asks
beyond that point, dissipating `f P` per unit slide, and the memory of the partial slip before is erased;
on reversal the contact sticks and slips again from the edges, along Mindlin & Deresiewicz's branch from
the sliding extreme. Under force control `|Q| >= f P` stays an error (`GrossSlipError`). Under a constant
`P` every model that runs a history of `delta` follows gross slip: the exact model of `Q` alone (a
symmetric profile, no bulk tension) and method 4 with a bulk tension `sigma`, on the Chebyshev grid
(`fr.models.Grid`), the Galerkin mesh with its nodes given (`fr.models.Mesh(theta=...)`) and the cells of
`fr.models.Varying` (the default where `sigma` moves off the in-phase line). Under a varying `P` the exact
model of Jäger's superposition (`fr.models.Jaeger`, the default without `sigma`) and the cells of
`fr.models.Varying` follow `delta` into gross slip and back, sliding at `f P(t)`
([theory](../theory/displacement.md#varying-load)).

With `sigma` the contact slides with `q = +-f p` everywhere and each point slips by the step's `d delta`
plus the strain mismatch of the change of `sigma`, `d sigma x / (2 E_star)`; a slide dissipates `f P |d delta|`.
A change of `sigma` larger than the slide can carry (`|d sigma| a / (2 E_star) > |d delta|`) would take one
edge against `Q`: that side sticks, `|Q|` falls below `f P` and the step is partial slip
([theory](../theory/displacement.md#sliding-sigma)):

```python
from fretting.models.galerkin import uniform_theta

history = fr.History.piecewise_linear(delta=[0, 0, 3e-6, 3.5e-6], sigma=[0, 50e6, 50e6, 80e6], steps_per_segment=16)
result = fr.simulate(contact, history, fr.models.Mesh(theta=uniform_theta(128)))
result.regime                            # 2 where the contact slides under the tension
```

## A fretting-wear test that runs into gross slip and back

The shipped example `{EXAMPLE}` (`fretting run {EXAMPLE}`; the history file
`histories/{EXAMPLE}.toml`) drives the contact above by `delta`: three cycles of +-1 um, three
of +-3 um and three of +-0.25 um. Its contact starts to slide whole at `delta_t` = {delta_t * 1e6:.4g} um
(`fretting.studies.running.transition_displacement`), so the middle block slides at each end. It ran in
{run_seconds:.1f} s ({len(history)} steps). Its loops:

![Fretting loops of cycles 1, 4 and 7](../validation/figures/displacement_loops.png)

and what `fretting.studies.running.loop_cycles(result)` makes of each cycle (`Q*/(f P)`, `delta*` [um],
the opening `2 delta_0` at `Q = 0` [um], the energy `E_d` [mJ/m], Fouvry's ratios `A = E_d / (4 Q*
delta*)` and `B = delta_0 / delta*`, the regime):

{table(["cycle", "Q*/(f P)", "delta* [um]", "2 delta_0 [um]", "E_d [mJ/m]", "A", "B", "regime"], cycle_rows)}

The last block stays on the branch from the last slide at `+f P`, so its loops do not cross `Q = 0`:
their opening and `B` are not defined (-). Its first cycle dissipates more than the next: its first
fall to `-0.25` um goes on down that branch, and only then do the small loops close on themselves.

The run writes these numbers into its result, per cycle (`Q_amplitude`, `delta_amplitude`, `loop_opening`,
`energy_ratio`, `sliding_ratio` and `cycle_regime` beside `cycle_dissipation`), from the steps it records:
a cycle whose steps are not all recorded (`record=`, or the first and last steps only of a history of
over 20 000 steps) has NaN and regime -1, and a run cut into parts, resumed or in chunks writes the
numbers of the run in one piece, bit for bit. `loop_cycles` reads them, and computes them from the
steps of a result written by an earlier version.

Which of these depend on the datum: `delta*`, `A` and `B` do (they carry the stuck contact's `K Q`); for a
given history of `Q`, `Q*`, the opening and `E_d` do not
([what depends on the datum](../theory/displacement.md#datum-dependence)).

## A running-condition map

`fretting.studies.running.running_map(contact, P, delta_amplitude)` runs {CYCLES} cycles of `+-delta*`
from rest at each normal load and amplitude with the exact model, in this process, as the cases of a
sweep (`fretting.studies.sweeps.run_cases`), and keeps the last cycle's numbers;
`fretting.plots.running_condition_map` draws a variable of it over `(delta*, P)`, with the boundary
`delta_t(P)`. The contact above over {LOADS.size} loads and {AMPLITUDES.size} amplitudes took
{map_seconds:.0f} s:

![The regime and the energy ratio over P and delta*](../validation/figures/running_map.png)

The boundary, `delta_t = (C_L + C) f P + delta_Q(f P)` (eq D6), grows with `P` through both terms:

{table(["P [kN/m]", "delta_t [um]", "f P [kN/m]"], boundary_rows)}

Points left of it run in partial slip, points right of it in gross slip. `A` jumps at the boundary and
grows toward 1 as sliding takes over the cycle; its value at the transition depends on the datum, so
read the regime from `cycle_regime` (or from `delta_t`) rather than from a threshold on `A`.

## A running-condition map from a sweep file

A [sweep](sweeps.md) over the normal load `contact.P` and the amplitude `delta_amplitude` of a `sine`
block of `delta` makes the same map with the sweep machinery: cases run on dask (a local cluster, a
scheduler, or a job array), each kept in its file so that an interrupted sweep resumes. The shipped
`histories/sweeps/hertz_running_map.toml` holds its base history (the contact above, three sine cycles
of `delta` from rest) and the grid:

```toml
[grid]
"contact.P" = [25e3, 50e3, 100e3, 150e3, 200e3]                             # [N/m]
"loading[1].delta_amplitude" = [0.25e-6, 0.5e-6, 1e-6, 1.5e-6, 2.5e-6, 4e-6]  # [m]
```

```
fretting sweep hertz_running_map                 # results/hertz_running_map.h5
fretting plot results/hertz_running_map.h5       # ..._running_cycle_regime.png, ..._running_energy_ratio.png
```

Each case of the file keeps its last cycle's loop (`cycle_regime`, `Q_amplitude`, `loop_opening`,
`energy_ratio`, `sliding_ratio`, with `energy_per_cycle`) and its contact's boundary `transition`;
`fretting plot` draws the regime and `A` over `(delta*, P)` with the boundary, as above, and
`fretting.studies.running.running_cases(fretting.studies.sweeps.load_sweep(path))` gives the map on
`(P, delta_amplitude)` as `running_map` does.

## The datum of a rig, from a measured loop

A measured partial-slip loop, as a CSV file with columns `delta` [m] and `Q` [N/m], gives the datum
that reproduces its elastic slope:

```python
from fretting.studies import running

delta, Q = running.read_loop("loop.csv")
L, K = running.fit_datum(contact, delta, Q)   # contact: its profile, moduli, f, P and C
```

`fit_datum` runs the exact model on the measured `Q`, takes away its slip part `delta_Q`, and fits the
line `delta - delta_Q = K Q + delta_0`; `L` is the datum whose stuck compliance is `K - C`. Use it in
`fr.Contact(..., datum=L, compliance=C)` to model the rig.
"""
