"""Regenerate the validation pages of the documentation and the examples gallery.

Run from the repository root:  python scripts/make_validation.py [--only closed-forms trajectories ...]

Writes docs/validation/{closed-forms,trajectories,performance,galerkin-constants}.md, docs/examples.md,
docs/guide/size-effect.md and docs/guide/displacement.md, with their
figures in docs/validation/figures/ (100 dpi). Every figure and table is computed here, by the
engine against closed forms or against the converged references of benchmarks/trajectories.py
(cached in benchmarks/.cache), and each page is stamped with the version, the UTC date and this
command. The gallery copies the figures of results/ (scripts/make_results.py) that it shows.
"""

import argparse
import datetime
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

import fretting as fr  # noqa: E402
from fretting.analysis.accuracy import BAND, monotonic_dissipation, traction_error, zone_distance, zone_pairs  # noqa: E402
from fretting.loading.examples import EXAMPLES, examples  # noqa: E402
from fretting.physics import closed_forms as cf  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
import displacement_guide  # noqa: E402
import engine_speed  # noqa: E402
import galerkin_constants  # noqa: E402
import size_effect  # noqa: E402
import stepping  # noqa: E402
import trajectories  # noqa: E402

DOCS = ROOT / "docs"
PAGES = DOCS / "validation"
FIGURES = PAGES / "figures"
RESULTS = ROOT / "results"
COMMAND = "python scripts/make_validation.py"
DPI = 100

#: Cattaneo-Mindlin loads ``Q/(f P)``, and Nowell-Hills loads ``(Q/(f P), sigma/(f p0))`` (inside
#: the closed form's range ``|sigma|/(f p0) <= 2 Q/(f P)``).
CATTANEO_MINDLIN = (0.2, 0.5, 0.8, 0.95)
NOWELL_HILLS = ((0.5, 0.5), (0.4, 0.8), (0.7, -0.3), (0.8, 1.2))
#: Steps of the straight path from the unloaded contact to each load.
STEPS = 8
#: Grid sizes and steps of the speed-against-error scene.
GRIDS = (64, 128, 256, 384, 768)
SPEED_STEPS = 128
#: Gallery figures per example, the most telling of `fretting plot`'s: of each group the first that
#: `fretting plot` drew (a history without Q has sigma loops only).
GALLERY = (("loops", "sigma_loops"), ("traction",), ("dissipation_density",))
#: Colours of the gallery's copies of the figures of results/.
PALETTE = 64


# -- Pages ------------------------------------------------------------------------------------------


def stamp(what):
    """The page's provenance: version, UTC date, the command that regenerates it and what it ran."""
    today = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return (
        f'!!! info "Generated"\n    fretting {fr.__version__}, {today}, by `{COMMAND}` '
        f"(regenerate with that command from the repository root). {what}\n"
    )


def write_page(path, title, what, body):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"# {title}\n\n{stamp(what)}\n{body.strip()}\n")
    print(f"wrote {path.relative_to(ROOT)}", flush=True)


def save_figure(fig, name):
    FIGURES.mkdir(parents=True, exist_ok=True)
    fig.savefig(FIGURES / name, dpi=DPI, bbox_inches="tight")
    plt.close(fig)


def markdown_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + " --- |" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows])


def verdict(value, target):
    """``value`` in scientific notation, marked when it misses ``target``."""
    return f"{value:.1e}" + ("" if value <= target else " **over**")


# -- Closed forms -----------------------------------------------------------------------------------


def proportional(contact, psi, tau=0.0):
    """The default's straight path to ``Q = psi f P``, ``sigma = tau f p0``: its last step, its
    model and nodes, and the energy [J/m] it dissipated on the way."""
    history = fr.History.piecewise_linear(
        [0.0, psi * contact.f * contact.P], [0.0, tau * contact.f * contact.p0], STEPS
    )
    result = fr.simulate(contact, history)
    energy = float(result.dissipation.sum())
    return result.isel(step=-1), result.attrs["model"], int(result.attrs["nodes"]), energy


def errors(contact, step, expected_zone, q_exact, slip_exact=None):
    """Stick-end [a], traction [f p0] (away from the stick ends and edges) and slip errors of one step."""
    a, x = contact.a, step.x.values
    exclude = np.r_[expected_zone, -a, a]
    zones = zone_pairs(step.stick_start.values, step.stick_end.values)
    row = {
        "stick": zone_distance(zones, np.array([expected_zone])) / a,
        "traction": traction_error(x, step.q.values, q_exact, exclude, BAND * a) / (contact.f * contact.p0),
    }
    if slip_exact is not None:
        row["slip"] = np.abs(step.slip.values - slip_exact).max() / np.abs(slip_exact).max()
    return row


def cycle_energy_error(contact, psi):
    """``|W/W_ref - 1|`` of the default's steady cycle between ``-Q*`` and ``Q*`` (Mindlin & Deresiewicz)."""
    Q_star = psi * contact.f * contact.P
    history = fr.History.piecewise_linear([0.0, Q_star, -Q_star, Q_star], None, 16)
    result = fr.simulate(contact, history)
    W = result.dissipation.values[history.vertex_step[1] + 1 :].sum()
    return abs(W / cf.mindlin_deresiewicz_energy(contact, Q_star) - 1)


def closed_forms_page():
    contact = trajectories.hertz()
    a, fp0 = contact.a, contact.f * contact.p0
    rows, shown = [], {}
    for psi in CATTANEO_MINDLIN:
        Q = psi * contact.f * contact.P
        step, model, nodes, _ = proportional(contact, psi)
        x = step.x.values
        b = cf.stick_half_width(contact, Q)
        q, s = cf.cattaneo_mindlin_traction(contact, Q, x), cf.cattaneo_mindlin_slip(contact, Q, x)
        e = errors(contact, step, [-b, b], q, s) | {"energy": cycle_energy_error(contact, psi)}
        rows.append(("Cattaneo-Mindlin", f"{psi}", "0", f"{model} ({nodes})", e))
        if psi == 0.5:
            shown["cm"] = (step, q, s)
    for psi, tau in NOWELL_HILLS:
        Q, sigma = psi * contact.f * contact.P, tau * fp0
        step, model, nodes, energy = proportional(contact, psi, tau)
        b, centre = cf.stick_half_width(contact, Q), cf.nowell_hills_offset(contact, sigma)
        q = cf.nowell_hills_traction(contact, Q, sigma, step.x.values)
        e = errors(contact, step, [centre - b, centre + b], q)
        e["energy"] = abs(energy / monotonic_dissipation(contact, Q, sigma / Q) - 1)
        rows.append(
            (
                "Nowell-Hills",
                f"{psi}",
                f"{tau}",
                f"{model} ({nodes})",
                e,
            )
        )
        if (psi, tau) == (0.5, 0.5):
            shown["nh"] = (step, q)
    targets = {"stick": 1e-3, "traction": 1e-3, "slip": 1e-3, "energy": 1e-4}
    table = markdown_table(
        [
            "closed form",
            "Q/(f P)",
            "sigma/(f p0)",
            "model (nodes)",
            "stick ends [a]",
            "traction [f p0]",
            "slip [max]",
            "energy",
        ],
        [(*row[:4], *(verdict(row[4][k], targets[k]) if k in row[4] else "-" for k in targets)) for row in rows],
    )
    closed_forms_figure(contact, shown)
    body = f"""
The default model (`fr.simulate` with no model) against published closed forms on a Hertz contact
(R = 50 mm, E* of steel, f = 0.6, P = 100 N/mm: a = {a * 1e3:.3f} mm, f p0 = {fp0 / 1e6:.0f} MPa),
each load reached from the unloaded contact in {STEPS} equal steps. Under Q alone the default is
the exact model (the Ciavarella-Jaeger superposition with Masing's rule), which evaluates these
closed forms at its nodes, so its errors are rounding; under Q and sigma it is method 4 on a
Galerkin mesh adapted to the history, and its errors are those of the discretisation.

- **Cattaneo-Mindlin** (Q alone): traction eq (7), stick half-width ``b = a sqrt(1 - Q/(f P))``
  eq (8), slip eq (19) integrated (`fretting.physics.closed_forms.cattaneo_mindlin_traction`,
  `cattaneo_mindlin_slip`, `stick_half_width`); the energy of a steady cycle between ``-Q*`` and
  ``Q*`` (16 steps per reversal) against Mindlin & Deresiewicz (1953), `mindlin_deresiewicz_energy`.
- **Nowell-Hills** (Q and sigma in phase from zero, Nowell & Hills 1987): the stick zone of
  half-width ``b`` moved by ``e = -sigma a/(4 f p0)`` (`nowell_hills_offset`), traction
  `nowell_hills_traction`; the energy dissipated on the way, ``int f p |s| dx`` of its slip
  (`fretting.analysis.accuracy.monotonic_dissipation`, by quadrature).

## Worst errors

Stick ends: `fretting.analysis.accuracy.zone_distance` from the closed form's zone, in units of a.
Traction: largest ``|q - q_ref|`` in units of f p0 away from ({BAND} a around) the stick ends and
the contact edges, where the closed form has a square-root kink
(`fretting.analysis.accuracy.traction_error`). Slip: largest ``|s - s_ref|`` relative to the
largest slip (no closed form under sigma). Energy: ``|W/W_ref - 1|``, of the steady cycle
(Cattaneo-Mindlin) or of the path from zero (Nowell-Hills). Targets: 1e-3 a, 1e-3 f p0, 1e-3 and 1e-4; a value marked
**over** misses its target. "-": no closed form.

{table}

## Traction and slip

![Computed traction and slip against the closed forms](figures/closed_forms.png)

Left: Cattaneo-Mindlin at Q = 0.5 f P; middle: its slip; right: Nowell-Hills at Q = 0.5 f P,
sigma = 0.5 f p0. Lines: closed form; dots: the default's nodes.
"""
    write_page(PAGES / "closed-forms.md", "Closed forms", "It ran the default on the loads in the table below.", body)


def closed_forms_figure(contact, shown):
    a, fp0 = contact.a, contact.f * contact.p0
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.4))
    (step, q, s), (nh_step, nh_q) = shown["cm"], shown["nh"]
    for ax, data, exact, label in (
        (axes[0], step.q.values / fp0, q / fp0, "q / (f p0)"),
        (axes[1], step.slip.values * 1e6, s * 1e6, "slip [um]"),
        (axes[2], nh_step.q.values / fp0, nh_q / fp0, "q / (f p0)"),
    ):
        x = (step if ax is not axes[2] else nh_step).x.values / a
        ax.plot(x, exact, "k-", lw=1, label="closed form")
        ax.plot(x, data, ".", ms=3, color="C3", label="computed")
        ax.set_xlabel("x / a")
        ax.set_ylabel(label)
    axes[0].set_title("Cattaneo-Mindlin, Q = 0.5 fP")
    axes[1].set_title("Cattaneo-Mindlin slip")
    axes[2].set_title("Nowell-Hills, Q = 0.5 fP, sigma = 0.5 fp0")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, "closed_forms.png")


# -- Trajectories -----------------------------------------------------------------------------------


def scored(contact, history, ref, run):
    """``(model, nodes, seconds, worst)`` of `run` (a function giving a result) against `ref`."""
    began = time.perf_counter()
    result = run()
    seconds = time.perf_counter() - began
    worst = trajectories.score(trajectories.fields_of(result), ref, contact, history)
    return trajectories._label(result.attrs), int(result.attrs["nodes"]), seconds, worst


def worst_table(rows):
    """Markdown table of `trajectories.score`'s worst errors, one row per history, with the targets."""
    targets = trajectories.TARGETS
    return markdown_table(
        ["history", "steps", "model", "nodes", "s", *targets],
        [
            (name, steps, model, nodes, f"{seconds:.2f}")
            + tuple(f"{verdict(worst[n][0], targets[n])} @ {worst[n][1]}" for n in targets)
            for name, steps, model, nodes, seconds, worst in rows
        ]
        + [("target", "", "", "", "", *(f"{targets[n]:.0e}" for n in targets))],
    )


def trajectories_page():
    selected = trajectories.cases()
    uniform = {"check": trajectories.CHECK_ELEMENTS, "reference": trajectories.REFERENCE_ELEMENTS}
    rows, checks = [], []
    for name in trajectories.QUICK:
        contact, history = selected[name]
        ref = trajectories.with_located_ends(trajectories.fine_run(contact, history, uniform["reference"]), contact)
        check = trajectories.with_located_ends(trajectories.fine_run(contact, history, uniform["check"]), contact)
        worst = trajectories.score(check, ref, contact, history)
        checks.append((name, len(history), "uniform", uniform["check"] + 1, check["seconds"], worst))
        rows.append(
            (name, len(history), *scored(contact, history, ref, lambda c=contact, h=history: fr.simulate(c, h)))
        )
        print(f"  {name}: default {rows[-1][4]:.1f} s", flush=True)
    targets = trajectories.TARGETS
    names = list(targets)
    table, check_table = worst_table(rows), worst_table(checks)
    met = [
        f"- `{n}`: met by {sum(w[n][0] <= targets[n] for *_, w in rows)} of {len(rows)} histories; "
        f"worst {max(w[n][0] for *_, w in rows):.1e}"
        for n in names
    ]
    body = f"""
Every step of general Q/sigma histories against a converged reference: the quick subset of
`benchmarks/trajectories.py` ({", ".join(f"`{n}`" for n in trajectories.QUICK)}), each run with
the default (`fr.simulate(contact, history)`) and on a uniform Galerkin mesh of
{trajectories.REFERENCE_ELEMENTS} elements in theta (the reference, cached in benchmarks/.cache).
The full set of about 30 histories is `python benchmarks/trajectories.py`.

Per history ("s": the default's wall time on a shared machine), the worst over its steps, with the
step where it occurs (`@`):

- `stick_a`: distance of the stick zones from the reference's [a];
- `slip_history`: ``max |s - s_ref|`` relative to the history's largest slip; `slip_step`: relative
  to the step's own largest slip (after step {trajectories.FIRST_STEPS});
- `traction_fp0`: ``max |q - q_ref|`` [f p0] away from {BAND} a around the stick ends, the former
  boundaries that the slip remembers and the contact edges;
- `energy`: ``|W/W_ref - 1|`` of the energy dissipated from the start to each vertex and of each cycle.

The targets are those of issue 18 (1e-3 a, 1e-3, 1e-3, 1e-3 f p0, 1e-4); **over** marks a miss.

{table}

{chr(10).join(met)}

## The reference's own error

The same histories on a uniform mesh of {trajectories.CHECK_ELEMENTS} elements, scored against the
reference like the default ("s": this run's wall time when it was cached). Where the error falls at
least in proportion to the element size, the reference's own error is no larger than these
differences; where one of them is close to the default's above, that table cannot tell the
default's error from the reference's.

{check_table}
"""
    write_page(
        PAGES / "trajectories.md",
        "Accuracy over general histories",
        "It ran the quick subset of benchmarks/trajectories.py.",
        body,
    )


# -- Performance ------------------------------------------------------------------------------------


def in_phase_errors(contact, psi, tau, **model):
    """CPU ms per step, nodes, model and errors (`errors`) of a straight in-phase path of
    `SPEED_STEPS` steps to ``Q = psi f P``, ``sigma = tau f p0``, against Nowell-Hills."""
    Q, sigma = psi * contact.f * contact.P, tau * contact.f * contact.p0
    history = fr.History.piecewise_linear([0.0, Q], [0.0, sigma], SPEED_STEPS)
    seconds, result = engine_speed.cpu(lambda: fr.simulate(contact, history, **model), 3)
    step = result.isel(step=-1)
    b, centre = cf.stick_half_width(contact, Q), cf.nowell_hills_offset(contact, sigma)
    e = errors(contact, step, [centre - b, centre + b], cf.nowell_hills_traction(contact, Q, sigma, step.x.values))
    return 1e3 * seconds / SPEED_STEPS, int(result.attrs["nodes"]), result.attrs["model"], e


def performance_page():
    contact = trajectories.hertz()
    runs = [(f"grid {n}", {"nodes": n}) for n in GRIDS] + [("default", {}), ("rtol 1e-5", {"rtol": 1e-5})]
    speed = [(label, *in_phase_errors(contact, 0.5, 0.5, **model)) for label, model in runs]
    speed_table = markdown_table(
        ["run", "model", "nodes", "ms/step", "stick ends [a]", "traction [f p0]"],
        [
            (label, name, nodes, f"{ms:.2f}", f"{e['stick']:.1e}", f"{e['traction']:.1e}")
            for label, ms, nodes, name, e in speed
        ],
    )
    stepped = []
    for label, history, model in stepping.histories():
        whole_time, step_time, same = stepping.compared(history, model)
        ratio = step_time / whole_time
        stepped.append(
            (
                label,
                len(history),
                f"{1e6 * whole_time:.1f}",
                f"{1e6 * step_time:.1f}",
                f"{ratio:.2f}" if ratio <= stepping.TARGET else f"**{ratio:.2f}**",
                "yes" if same else "**no**",
            )
        )
    stepping_table = markdown_table(
        ["scene", "steps", "simulate [us/step]", "stepped [us/step]", "ratio", "bit for bit"], stepped
    )
    speed_figure(speed)
    body = f"""
## Speed against error

A Hertz contact (as on [Closed forms](closed-forms.md)) taken from the unloaded state to
Q = 0.5 f P, sigma = 0.5 f p0 in {SPEED_STEPS} equal in-phase steps, scored at the last step against
the Nowell-Hills closed form (stick ends in a; traction in f p0 away from {BAND} a around the stick
ends and edges), on Gauss-Chebyshev grids (`nodes=`), with the default (a Galerkin mesh adapted to
the history) and with a finer adapted mesh (`rtol=1e-5`). CPU time per step, best of 3, one core of
a shared machine; it includes building the model (and adapting the mesh), so it bounds a long
run's cost per step from above.

{speed_table}

![Error against CPU time per step](figures/speed_vs_error.png)

The full comparison over several scenes and accuracy settings is `python benchmarks/speed_vs_error.py`.

## Stepping from Python

`benchmarks/stepping.py`: one history run by `fr.simulate` and by a loop of `fr.Stepper.step`
calls with the same model, CPU time per step (the least of 5 timings, each of as many runs as fill
0.2 s); the target is a ratio of at most {stepping.TARGET} on every model (in bold where missed).
"Bit for bit" compares the slip and the energy of every step.

{stepping_table}
"""
    write_page(
        PAGES / "performance.md",
        "Performance",
        "It ran the scenes below, timed by CPU time on one core of a shared machine.",
        body,
    )


def speed_figure(speed):
    """Stick-end and traction errors against CPU time per step: the grids as a line, the meshes as points."""
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    grids = [row for row in speed if row[0].startswith("grid")]
    for ax, key, label in ((axes[0], "stick", "stick-end error [a]"), (axes[1], "traction", "traction error [f p0]")):
        ax.loglog([row[1] for row in grids], [row[4][key] for row in grids], "o-", label="grids")
        for (name, ms, nodes, _, e), marker in zip(speed[len(grids) :], "s^", strict=True):
            ax.loglog(ms, e[key], marker, label=f"{name} ({nodes} nodes)")
        for _, ms, nodes, _, e in grids:
            ax.annotate(str(nodes), (ms, e[key]), textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax.set_xlabel("CPU ms per step")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, "speed_vs_error.png")


# -- Examples ---------------------------------------------------------------------------------------

#: The worked study, shown on the page and run here (``exec``), so that the page shows what ran.
STUDY = """
import matplotlib.pyplot as plt
import numpy as np

import fretting as fr

contact = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)
fP, fp0 = contact.f * contact.P, contact.f * contact.p0
Q_amplitudes = np.array([0.2, 0.4, 0.6])      # Q / (f P)
sigma_amplitudes = np.array([0.0, 0.3, 0.6])  # sigma / (f p0)
energy = np.zeros((Q_amplitudes.size, sigma_amplitudes.size))
for i, psi in enumerate(Q_amplitudes):
    for j, tau in enumerate(sigma_amplitudes):
        history = fr.History.sinusoidal(psi * fP, tau * fp0, phase_deg=0, cycles=2, steps_per_cycle=32)
        result = fr.simulate(contact, history)
        energy[i, j] = result.cycle_dissipation.values[-1]  # the second, steady cycle [J/m]

fig, ax = plt.subplots(figsize=(4.5, 3.5))
mesh = ax.pcolormesh(sigma_amplitudes, Q_amplitudes, energy * 1e3, shading="nearest")
fig.colorbar(mesh, label="energy per cycle [mJ/m]")
ax.set_xlabel("sigma amplitude / (f p0)")
ax.set_ylabel("Q amplitude / (f P)")
for i, psi in enumerate(Q_amplitudes):
    for j, tau in enumerate(sigma_amplitudes):
        ax.text(tau, psi, f"{energy[i, j] * 1e3:.2f}", ha="center", va="center", color="w", fontsize=8)
"""


def gallery_figures(name):
    """Copy `GALLERY`'s figures of example `name` from results/ into the docs, reduced to a palette
    of `PALETTE` colours (a third of the size; the figures are line plots); their file names."""
    copied = []
    for group in GALLERY:
        drawn = [path for path in (RESULTS / f"{name}_{figure}.png" for figure in group) if path.is_file()]
        if not drawn:
            missing = RESULTS / f"{name}_{group[0]}.png"
            raise FileNotFoundError(f"{missing} missing: run python scripts/make_results.py first")
        source = drawn[0]
        FIGURES.mkdir(parents=True, exist_ok=True)
        with Image.open(source) as image:
            image.convert("RGB").quantize(colors=PALETTE).save(FIGURES / source.name, optimize=True)
        copied.append(source.name)
    return copied


def leading_comment(path):
    """The comment that opens the history file `path`, as Markdown paragraphs."""
    lines = []
    with path.open(encoding="utf-8") as text:
        for line in text:
            if not line.startswith("#"):
                break
            lines.append(line.removeprefix("#").strip())
    return "\n".join(lines)


def examples_page():
    sections = []
    for name in examples():
        images = "\n".join(f'![{name}: {f}](validation/figures/{f}){{ width="32%" }}' for f in gallery_figures(name))
        sections.append(
            f"## {name}\n\n{leading_comment(EXAMPLES / f'{name}.toml')}\n\n"
            f"Run it: `fretting run {name}` (the history file: `histories/{name}.toml`), "
            f"then `fretting plot {name}.h5`.\n\n{images}\n"
        )
    scope = {}
    exec(compile(STUDY, "<study>", "exec"), scope)  # noqa: S102 - the study shown on the page
    scope["fig"].tight_layout()
    save_figure(scope["fig"], "study_fretting_map.png")
    body = f"""
Each history shipped with the package (`fretting examples` lists them), what it models, and three of
the figures that `fretting plot` draws from its result (the hysteresis loops of Q and sigma against
their generalised displacements, the traction at the load peaks, and the energy dissipated per unit
area in each cycle). The figures come from results/, which `python scripts/make_results.py`
regenerates; this page copies them.

{chr(10).join(sections)}
## A worked study: a small fretting map

The energy dissipated per steady cycle of in-phase shear force and bulk tension on the Hertz
contact of the [validation pages](validation/closed-forms.md), over a 3 x 3 grid of amplitudes.
This script is what `{COMMAND}` runs to draw the figure below. For larger grids, in parallel and
with files, see [Sweeps](guide/sweeps.md).

```python
{STUDY.strip()}
```

![Energy per cycle over Q and sigma amplitudes](validation/figures/study_fretting_map.png)
"""
    write_page(DOCS / "examples.md", "Examples", "It copied the figures of results/ and ran the study below.", body)


# -- Galerkin constants -----------------------------------------------------------------------------


def galerkin_constants_page():
    write_page(
        PAGES / "galerkin-constants.md",
        "Galerkin tuning constants",
        "It reran the comparisons of scripts/galerkin_constants.py.",
        galerkin_constants.body(markdown_table),
    )


# -- The size effect ---------------------------------------------------------------------------------


def size_effect_page():
    write_page(
        DOCS / "guide" / "size-effect.md",
        "A fretting-fatigue map: the size effect",
        "It ran the study of scripts/size_effect.py.",
        size_effect.body(markdown_table, save_figure),
    )


# -- Displacement control ----------------------------------------------------------------------------


def displacement_page():
    write_page(
        DOCS / "guide" / "displacement.md",
        "Displacement control, gross slip and fretting maps",
        "It ran the example and the map of scripts/displacement_guide.py.",
        displacement_guide.body(markdown_table, save_figure),
    )


PAGE_BUILDERS = {
    "closed-forms": closed_forms_page,
    "trajectories": trajectories_page,
    "performance": performance_page,
    "examples": examples_page,
    "galerkin-constants": galerkin_constants_page,
    "size-effect": size_effect_page,
    "displacement": displacement_page,
}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", choices=list(PAGE_BUILDERS), help="pages to regenerate (default: all)")
    args = parser.parse_args(argv)
    for name in args.only or PAGE_BUILDERS:
        began = time.perf_counter()
        PAGE_BUILDERS[name]()
        print(f"{name}: {time.perf_counter() - began:.0f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
