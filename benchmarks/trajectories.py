"""Every step of arbitrary Q/sigma histories against a converged reference (issue 18).

Builds about 30 histories of the kinds issue 18 lists (random walks of Q and sigma with reversals,
ellipses at 45, 90 and 135 degrees, box and L-shaped paths, near sliding up to 0.999 fP, amplitudes
of 1e-4 fP, sigma up to 3 f p0, rounded flats with b/a = 0.25 and 0.75, asymmetric gap profiles),
runs each on a uniform Galerkin mesh of `REFERENCE_ELEMENTS` elements in ``theta`` (the reference)
and of `CHECK_ELEMENTS` (its convergence check: scored against the reference like any run, its
errors bound the reference's own; for the small amplitudes of `BANDED`, whose cyclic slip zones
are narrower than those elements, the reference's elements there are bisected and the check's
once fewer), then scores the default (and optionally ``rtol=1e-4`` and the
384-node grid) at every step:

- stick ends [a]: `fretting.analysis.accuracy.zone_distance` of the step's stick zones;
- slip: ``max |s - s_ref|`` over the run's nodes (``s_ref`` interpolated linearly), relative to
  the history's largest slip, and relative to the step's largest slip after step `FIRST_STEPS`;
- traction [f p0]: `fretting.analysis.accuracy.traction_error`, leaving out `fretting.analysis.accuracy.BAND` a around
  the reference's stick ends of the step, the former boundaries its memory keeps
  (`fretting.analysis.accuracy.memory_kinks`) and the contact edges;
- energy [-]: ``|W / W_ref - 1|`` of the energy dissipated from the start to each vertex, and
  of each load cycle.

Each is the worst over the steps (with the step where it occurs). The targets are `TARGETS`.
References are cached in `CACHE` (gitignored), keyed by the contact, the loads and the mesh.

Run:  python benchmarks/trajectories.py [--quick] [--models default,rtol,grid] [--only NAME ...]
"""

import argparse
import hashlib
import time
from pathlib import Path

import numpy as np
from harness import FIRST_STEPS, asymmetric_flat

import fretting as fr
from fretting.analysis.accuracy import BAND, memory_kinks, traction_error, zone_distance, zone_pairs
from fretting.loading.examples import EXAMPLES
from fretting.models.galerkin import located_end, refine
from fretting.models.method4 import stick_zones

#: Elements of the uniform reference mesh in theta: 7.9e-4 a apart at the centre.
REFERENCE_ELEMENTS = 4000
#: Elements of the coarser mesh whose agreement with the reference shows it converged.
CHECK_ELEMENTS = 2000
#: Issue 18's targets at default settings.
TARGETS = {"stick_a": 1e-3, "slip_history": 1e-3, "slip_step": 1e-3, "traction_fp0": 1e-3, "energy": 1e-4}
#: Models scored: keywords of `fretting.simulate`.
MODELS = {"default": {}, "rtol": {"rtol": 1e-4}, "grid": {"nodes": 384}}
#: Histories whose reference has the elements that hold stick ends after the first vertex bisected
#: this many times (the check's one time fewer), `banded_mesh`: the small amplitudes, whose cyclic
#: slip zones are narrower than the uniform mesh's elements, and one ellipse whose uniform
#: reference locates its own stick ends to about its element only.
BANDED = {"tiny_1e-4_ellipse": 6, "tiny_1e-4_walk": 6, "ellipse_45": 2}
CACHE = Path(__file__).resolve().parent / ".cache" / "trajectories"
GAP_TABLE = EXAMPLES / "asymmetric_pad_gap.csv"
QUICK = ("walk_s0_8", "ellipse_90", "near_sliding_0.999", "flat_0.25_walk", "asym_flat_walk")


# -- Contacts -------------------------------------------------------------------------------------


def hertz():
    """R = 50 mm, steel, f = 0.6, P = 100 N/mm (a = 0.235 mm)."""
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


def rounded_flat(ratio, b=2e-4, P=1e5, f=0.6):
    """Rounded flat whose flat is `ratio` of the contact half-width: the corner radius from
    ``P = E_star a^2 (2e - sin 2e) / (4R)``, ``e = arccos(b/a)`` (Ciavarella, Hills & Monno 1998)."""
    E_star = fr.plane_strain_modulus(210e9, 0.3)
    a, e = b / ratio, np.arccos(ratio)
    R = E_star * a**2 * (2 * e - np.sin(2 * e)) / (4 * P)
    return fr.Contact(fr.RoundedFlat(b, R), E_star, f, P)


def asymmetric_gap_table():
    """The tabulated asymmetric pad of histories/asymmetric_pad_gap.csv (no breakpoints)."""
    x, h0 = np.loadtxt(GAP_TABLE, delimiter=",", skiprows=3, unpack=True)
    return fr.Contact(fr.Gap.from_table(x, h0), fr.plane_strain_modulus(210e9, 0.3), 0.7, 1e5)


def asymmetric_gap_flat():
    """Flat with corners of 10 and 40 mm (harness.asymmetric_flat), breakpoints at the flat's ends."""
    return fr.Contact(fr.Gap(*asymmetric_flat()), 115e9, 0.5, 3e5)


# -- Histories ------------------------------------------------------------------------------------


def walk(contact, seed, steps, vertices=10, Q_max=0.8, sigma_max=1.0, Q_mean=0.0, sigma_mean=0.0):
    """Random vertices from zero: ``Q/(f P)`` within ``Q_max`` of ``Q_mean``, ``sigma/(f p0)`` of ``sigma_mean``."""
    rng = np.random.default_rng(seed)
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    Q = (Q_mean + rng.uniform(-Q_max, Q_max, vertices)) * fP
    sigma = (sigma_mean + rng.uniform(-sigma_max, sigma_max, vertices)) * fp0
    return fr.History.piecewise_linear(np.r_[0.0, Q], np.r_[0.0, sigma], steps)


def path(contact, vertices, steps=16):
    """Straight segments through ``(Q/(f P), sigma/(f p0))`` vertices, from zero."""
    v = np.asarray([(0.0, 0.0), *vertices])
    return fr.History.piecewise_linear(v[:, 0] * contact.f * contact.P, v[:, 1] * contact.f * contact.p0, steps)


def ellipse(contact, phase, Q_amp=0.5, sigma_amp=0.8, cycles=2, steps=64, **means):
    """`fretting.History.sinusoidal` in units of ``f P`` and ``f p0``."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    scaled = {"Q_mean": means.get("Q_mean", 0.0) * fP, "sigma_mean": means.get("sigma_mean", 0.0) * fp0}
    return fr.History.sinusoidal(Q_amp * fP, sigma_amp * fp0, phase, cycles, steps, **scaled)


BOX = [(0.5, 0.0), (0.5, 0.8), (-0.5, 0.8), (-0.5, -0.8), (0.5, -0.8), (0.5, 0.0)]
L_PATH = [(0.7, 0.0), (0.7, 1.0), (0.7, 0.0), (-0.7, 0.0), (-0.7, -1.0), (-0.7, 0.0), (0.7, 0.0)]


def cases():
    """``name: (contact, history)`` of the benchmark."""
    h = hertz()
    flats = {ratio: rounded_flat(ratio) for ratio in (0.25, 0.75)}
    table, corners = asymmetric_gap_table(), asymmetric_gap_flat()
    out = {}
    for seed in range(4):
        for steps in (8, 16):
            out[f"walk_s{seed}_{steps}"] = (h, walk(h, seed, steps))
    for phase in (45, 90, 135):
        out[f"ellipse_{phase}"] = (h, ellipse(h, phase))
    out["ellipse_90_offset"] = (h, ellipse(h, 90, 0.3, 0.5, Q_mean=0.4, sigma_mean=0.3))
    out["box"] = (h, path(h, BOX))
    out["L_path"] = (h, path(h, L_PATH))
    out["near_sliding_0.999"] = (h, path(h, [(0.999, 0.3), (-0.999, -0.3), (0.999, 0.5)], 32))
    out["near_sliding_0.995_ellipse"] = (h, ellipse(h, 90, 0.3, 0.4, Q_mean=0.69))
    out["near_sliding_walk"] = (h, walk(h, 7, 16, 8, Q_max=0.999, sigma_max=0.5))
    out["tiny_1e-4_ellipse"] = (h, ellipse(h, 90, 1e-4, 1e-4, Q_mean=0.3, sigma_mean=0.2, steps=32))
    out["tiny_1e-4_walk"] = (h, walk(h, 3, 8, 8, Q_max=1e-4, sigma_max=1e-4, Q_mean=0.4))
    out["sigma_3_walk"] = (h, walk(h, 5, 16, 8, Q_max=0.5, sigma_max=3.0))
    out["sigma_3_ellipse"] = (h, ellipse(h, 60, 0.4, 3.0))
    for ratio, flat in flats.items():
        out[f"flat_{ratio}_walk"] = (flat, walk(flat, 11, 16, 8))
        out[f"flat_{ratio}_ellipse"] = (flat, ellipse(flat, 90))
    out["flat_0.75_near_sliding"] = (flats[0.75], path(flats[0.75], [(0.999, 0.3), (-0.99, -0.4), (0.999, 0.0)], 32))
    out["asym_table_walk"] = (table, walk(table, 13, 16, 8))
    out["asym_table_Q"] = (table, path(table, [(0.7, 0.0), (-0.6, 0.0), (0.5, 0.0), (-0.3, 0.0)]))
    out["asym_flat_walk"] = (corners, walk(corners, 17, 16, 8))
    out["asym_flat_ellipse"] = (corners, ellipse(corners, 135, 0.6, 1.0))
    return out


# -- Reference ------------------------------------------------------------------------------------

FIELDS = ("x", "slip", "q", "stick", "stick_start", "stick_end", "dissipation")


def _key(contact, history, elements):
    digest = hashlib.sha256(repr((repr(contact.profile), contact.E_star, contact.f, contact.P, elements)).encode())
    for values in (history.Q, history.sigma, history.vertex_step):
        digest.update(np.ascontiguousarray(values).tobytes())
    return digest.hexdigest()[:20]


def fine_run(contact, history, elements, bisections=0):
    """Fields of a run on the uniform mesh of `elements` elements in theta, cached in `CACHE`; with
    `bisections`, on that mesh with the elements of its cyclic slip zones bisected that many times
    (`banded_mesh`)."""
    path_ = CACHE / f"{_key(contact, history, (elements, bisections) if bisections else elements)}.npz"
    if path_.exists():
        with np.load(path_) as stored:
            return {name: stored[name] for name in FIELDS} | {"seconds": float(stored["seconds"])}
    mesh = np.linspace(0.0, np.pi, elements + 1)
    if bisections:
        mesh = banded_mesh(mesh, fine_run(contact, history, elements), history, bisections)
    began = time.perf_counter()
    result = fr.simulate(contact, history, mesh=mesh)
    fields = {name: result[name].values for name in FIELDS} | {"seconds": time.perf_counter() - began}
    CACHE.mkdir(parents=True, exist_ok=True)
    np.savez(path_, **fields)
    return fields


def banded_mesh(theta, fields, history, bisections):
    """`theta` [rad] with the elements that hold a stick/slip boundary of the run `fields` on it at
    any step after the history's first vertex, and two on either side, bisected `bisections` times
    (then graded): the cyclic slip zones of small amplitudes are narrower than a uniform mesh's
    elements."""
    status = np.sign(np.diff(fields["slip"][history.vertex_step[1] :], axis=0))[:, ::-1]  # theta order
    boundary = np.any(status[:, 1:] != status[:, :-1], axis=0)
    near = np.convolve(boundary, np.ones(5), mode="same") > 0
    targets = np.where(near, np.diff(theta) / 2**bisections, np.inf)
    return refine(theta, targets)


def fields_of(result):
    return {name: result[name].values for name in FIELDS}


def with_located_ends(fields, contact):
    """`fields` of a uniform-mesh run with its stick ends located anew from its slip, as the engine
    now locates them on a Galerkin mesh (so that cached references follow the engine's estimator).

    Each node's episode of slip in one direction starts where it last stuck or reversed, as
    `fretting.State.advance` keeps it; a node sticks where its slip did not change.
    """
    t = (fields["x"] - contact.centre) / contact.a
    slip = fields["slip"]
    start, ends = np.zeros(t.size), np.full((len(slip), t.size, 2), np.nan)
    for k in range(len(slip)):
        ds = slip[k] - slip[k - 1] if k else np.zeros(t.size)
        episode = slip[k - 1] - start if k else np.zeros(t.size)
        start = np.where(ds == 0, slip[k], np.where(np.sign(ds) * np.sign(episode) < 0, slip[k - 1], start))
        zones = stick_zones(t, slip[k] - start, located_end) if k else [(-1.0, 1.0)]
        ends[k, : len(zones)] = contact.centre + contact.a * np.array(zones).reshape(-1, 2)
    return fields | {"stick_start": ends[..., 0], "stick_end": ends[..., 1]}


# -- Scores ---------------------------------------------------------------------------------------


def score(run, ref, contact, history):
    """Worst errors of `run` against `ref` over the steps: ``name: (value, step)``."""
    a, fp0 = contact.a, contact.f * contact.p0
    edges = [contact.centre - a, contact.centre + a]
    x, xr = run["x"], ref["x"]
    kinks = memory_kinks(xr, ref["stick"])
    largest = np.abs(ref["slip"]).max()
    worst = {name: (0.0, 0) for name in TARGETS}

    def keep(name, value, step):
        if value > worst[name][0]:
            worst[name] = (float(value), int(step))

    for k in range(1, len(history)):
        ref_zones = zone_pairs(ref["stick_start"][k], ref["stick_end"][k])
        keep("stick_a", zone_distance(zone_pairs(run["stick_start"][k], run["stick_end"][k]), ref_zones) / a, k)
        error = np.abs(run["slip"][k] - np.interp(x, xr, ref["slip"][k])).max()
        keep("slip_history", error / largest if largest else 0.0, k)
        step_largest = np.abs(ref["slip"][k]).max()
        if k > FIRST_STEPS and step_largest > 0:
            keep("slip_step", error / step_largest, k)
        exclude = np.concatenate([ref_zones.ravel(), kinks[k], edges])
        q_ref = np.interp(x, xr, ref["q"][k])
        keep("traction_fp0", traction_error(x, run["q"][k], q_ref, exclude, BAND * a) / fp0, k)
    W, W_ref = np.cumsum(run["dissipation"]), np.cumsum(ref["dissipation"])
    for v in history.vertex_step:
        if W_ref[v] > 0:
            keep("energy", abs(W[v] / W_ref[v] - 1), v)
    if history.cycle is not None:
        for number in np.unique(history.cycle[history.cycle > 0]):
            steps = history.cycle == number
            cycle_ref = ref["dissipation"][steps].sum()
            if cycle_ref > 0:
                keep("energy", abs(run["dissipation"][steps].sum() / cycle_ref - 1), np.flatnonzero(steps)[-1])
    return worst


# -- Report ---------------------------------------------------------------------------------------


def _cell(value, step, target):
    flag = "*" if value > target else " "
    return f"{value:8.1e}{flag}@{step:<4d}"


def table(rows, title):
    names = list(TARGETS)
    print(f"\n## {title}\n")
    header = f"{'history':28} {'model':8} {'nodes':>5} {'s':>6} {'ms/step':>7} " + " ".join(f"{n:>15}" for n in names)
    print(header)
    for row in rows:
        cells = " ".join(_cell(*row["worst"][n], TARGETS[n]) for n in names)
        timing = f"{row['nodes']:5d} {row['seconds']:6.2f} {row['ms_step']:7.1f}"
        print(f"{row['name']:28} {row['model']:8} {timing} {cells}")
    print(f"{'targets':60} " + " ".join(f"{TARGETS[n]:>15.0e}" for n in names))
    for n in names:
        values = np.array([row["worst"][n][0] for row in rows])
        over = [row["name"] for row in rows if row["worst"][n][0] > TARGETS[n]]
        top = max(rows, key=lambda row: row["worst"][n][0])
        print(
            f"{n:14} median {np.median(values):.1e}  worst {top['worst'][n][0]:.1e} "
            f"({top['name']} step {top['worst'][n][1]})  over target: {len(over)} of {len(rows)} {over}"
        )
    seconds = np.array([row["seconds"] for row in rows])
    nodes = np.array([row["nodes"] for row in rows])
    print(
        f"time: median {np.median(seconds):.2f} s, max {seconds.max():.2f} s, total {seconds.sum():.1f} s; "
        f"nodes: median {np.median(nodes):.0f}, max {nodes.max()}"
    )


def _label(attrs):
    """The model a result ran (its ``model`` attribute), marked ``capped`` where the default fell back."""
    return attrs["model"] + (" capped" if "model_fallback" in attrs else "")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK)}")
    parser.add_argument("--models", default="default", help=f"comma-separated of {', '.join(MODELS)}")
    parser.add_argument("--only", nargs="*", help="history names to run")
    parser.add_argument("--no-check", action="store_true", help="skip the reference's convergence check")
    args = parser.parse_args(argv)
    selected = cases()
    names = args.only or (QUICK if args.quick else list(selected))
    rows = {model: [] for model in args.models.split(",")}
    checks = []
    for name in names:
        contact, history = selected[name]
        bisections = BANDED.get(name, 0)
        ref = with_located_ends(fine_run(contact, history, REFERENCE_ELEMENTS, bisections), contact)
        if not args.no_check:
            check_mesh = (REFERENCE_ELEMENTS, bisections - 1) if bisections else (CHECK_ELEMENTS, 0)
            check = with_located_ends(fine_run(contact, history, *check_mesh), contact)
            checks.append(
                {"name": name, "model": "mesh", "nodes": check["x"].size, "seconds": ref["seconds"]}
                | {"ms_step": 1e3 * ref["seconds"] / len(history), "worst": score(check, ref, contact, history)}
            )
        for model in rows:
            began = time.perf_counter()
            result = fr.simulate(contact, history, **MODELS[model])
            seconds = time.perf_counter() - began
            worst = score(fields_of(result), ref, contact, history)
            rows[model].append(
                {"name": name, "model": _label(result.attrs), "nodes": int(result.attrs["nodes"]), "seconds": seconds}
                | {"ms_step": 1e3 * seconds / len(history), "worst": worst}
            )
            print(f"{name:28} {model:8} {len(history):4d} steps {rows[model][-1]['model']:5} done", flush=True)
    if checks:
        table(
            checks,
            f"Reference convergence: {CHECK_ELEMENTS} against {REFERENCE_ELEMENTS} uniform elements, "
            f"{', '.join(BANDED)} as in BANDED (seconds: the reference's run)",
        )
    for model, model_rows in rows.items():
        table(model_rows, f"{model} ({MODELS[model] or 'fretting.simulate defaults'}) against the reference")


if __name__ == "__main__":
    main()
