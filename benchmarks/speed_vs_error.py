"""Speed against error: what each engine configuration costs and how right it is.

Run:  python benchmarks/speed_vs_error.py [--quick] [--out DIR] [--repeats N] [--long-timeout SECONDS]
      (results/: about 15 minutes on one core; --quick: a smoke test of about a minute)

Runs every configuration of `harness.configurations` (and the engine's defaults) on the scenes
of `harness.scenes`, times them (median of repeats, one core: the script runs itself again with
one BLAS thread unless ``--any-threads``), scores them against their references
(`fretting.analysis.accuracy`) and writes ``speed_vs_error.csv``, ``speed_vs_error.png`` and
``speed_vs_error.md`` in ``--out`` (default ``results``).
"""

import argparse
import csv
import itertools
import math
import os
import subprocess
import sys
from pathlib import Path

import harness

from fretting.analysis import accuracy

ERROR_TITLES = {
    "stick_ends_a": "stick-zone ends /a",
    "energy_rel": "energy per cycle (relative)",
    "traction_fp0": "traction /(f p0)",
}


# -- Writers ------------------------------------------------------------------------------------

CSV_COLUMNS = (
    "scene", "role", "label", "model", "kwargs", "points", "steps", "repeats", "total_s", "ms_per_step", "peak_MB",
    *harness.ERRORS, "reference",
)  # fmt: skip


def write_csv(rows, path):
    """One row per scene and configuration."""
    with open(path, "w", newline="") as file:
        writer = csv.DictWriter(file, CSV_COLUMNS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: f"{v:.6g}" if isinstance(v, float) else v for k, v in row.items()})
    return path


def write_png(rows, path):
    """Error against time per step, log-log, one panel per error; lines join one model's configurations."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.ticker import NullFormatter

    figure = Figure(figsize=(14, 4.6), layout="constrained")
    axes = figure.subplots(1, len(harness.ERRORS))
    names = list(dict.fromkeys(r["scene"] for r in rows))
    colours = dict(zip(names, matplotlib.colormaps["tab10"].colors, strict=False))
    for ax, error in zip(axes, harness.ERRORS, strict=True):
        for (name, model), group in itertools.groupby(
            sorted(
                (r for r in rows if r["role"] in ("engine", "baseline")),
                key=lambda r: (r["scene"], r["model"], r["points"]),
            ),
            key=lambda r: (r["scene"], r["model"]),
        ):
            group = [r for r in group if r[error] > 0]
            style = (
                {"ls": "--", "marker": "x", "mfc": "none"}
                if model == "baseline"
                else {"ls": "-", "marker": "o", "ms": 4}
            )
            label = f"{name} ({model})" if model != "chebyshev" else name
            ax.plot(
                [r["ms_per_step"] for r in group], [r[error] for r in group], color=colours[name], label=label, **style
            )
        for r in rows:
            if r["role"] == "default" and r[error] > 0:
                ax.plot(r["ms_per_step"], r[error], "*", color=colours[r["scene"]], ms=13, mec="k", mew=0.6)
        ax.set(xscale="log", yscale="log", xlabel="wall time per step [ms], one core", title=ERROR_TITLES[error])
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7, title="lines: configurations; star: default", title_fontsize=7)
    figure.savefig(path, dpi=130)
    return path


def _fmt(value, spec=".2e"):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return format(value, spec)


def _table(header, lines):
    out = [
        "| " + " | ".join(header) + " |",
        "|" + "|".join(" ---: " if i else " --- " for i in range(len(header))) + "|",
    ]
    return out + ["| " + " | ".join(str(cell) for cell in line) + " |" for line in lines]


def _field_table(rows, columns):
    """`_table` of the dicts `rows`; `columns` are ``(header, key, format)``, format None: the value as it is.

    A key a row lacks (a measurement not made) shows as ``-``.
    """
    header = tuple(title for title, _, _ in columns)
    cells = [[_fmt(row.get(key), spec or "") for _, key, spec in columns] for row in rows]
    return _table(header, cells)


def markdown(report, png_name):
    """The short report: how it was measured, one table per scene, the baseline, scaling, long runs."""
    meta, ratio = report["meta"], report["ratio"]
    lines = [
        "# Speed against error",
        "",
        f"`python benchmarks/speed_vs_error.py{' --quick' if meta['quick'] else ''}`, {meta['date']}, {meta['cpu']} "
        f"({meta['cores']} cores), one core ({meta['threads']}); {meta['versions']}. "
        f"Times are medians of {meta['repeats']} runs "
        f"(references: one run); peak memory is what tracemalloc saw in a separate run. The benchmark took "
        f"{meta['seconds']:.0f} s; load average at the end {meta['load']} (other processes share the cores).",
        "",
        "Errors are the largest over the steps (cycles) of a run: **stick ends** `/a`, distance between the "
        "stick-zone ends and the reference's (a zone, stick or slip, that only one of them has counts by half "
        "its width); **energy**, `|W/W_ref - 1|` per cycle; **traction** `/(f p0)`, "
        f"`|q - q_ref|` at the run's own points, leaving out {accuracy.BAND} a around each stick/slip boundary of the "
        "reference, those of the step and those its memory keeps (square-root kinks of the traction), and "
        "inside each contact edge. References of runs are interpolated linearly to the run's points.",
        "",
        f"![error against time per step]({png_name})",
        "",
        *_table(("scene", "history", "steps", "reference"), report["scenes"]),
    ]
    for name in dict.fromkeys(r["scene"] for r in report["rows"]):
        lines += ["", f"## {name}", ""]
        scene_rows = [r for r in report["rows"] if r["scene"] == name]
        lines += _table(
            ("configuration", "points", "ms/step", "total s", "peak MB", "stick ends /a", "energy", "traction /fp0"),
            [
                (
                    f"**{r['label']}**"
                    if r["role"] == "default"
                    else f"{r['label']}{' (reference)' if r['role'] == 'reference' else ''}",
                    r["points"],
                    _fmt(r["ms_per_step"], ".3g"),
                    _fmt(r["total_s"], ".3g"),
                    _fmt(r["peak_MB"], ".3g"),
                    *(_fmt(r[e]) for e in harness.ERRORS),
                )
                for r in scene_rows
            ],
        )
    lines += ["", "## Baseline", "", _ratio_text(ratio), "", "## Cost against resolution", ""]
    lines += _field_table(
        report["resolution"],
        [("model", "model", None), ("configuration", "label", None), ("points", "points", None),
         ("ms/step", "ms_per_step", ".3g"), ("exponent d ln t / d ln N", "exponent", ".2f"),
         ("peak MB", "peak_MB", ".3g")],
    )  # fmt: skip
    lines += ["", "## Cost against steps (default, Hertz Q cycling, last step recorded)", ""]
    lines += _field_table(
        report["steps"],
        [("cycles", "cycles", None), ("steps", "steps", None), ("total s", "total_s", ".3g"),
         ("ms/step", "ms_per_step", ".3g"), ("peak MB", "peak_MB", ".3g")],
    )  # fmt: skip
    lines += ["", "## Long runs (default settings, fresh process each)", ""]
    lines += _field_table(
        report["long"],
        [("target", "target", None), ("history", "title", None), ("cycles", "cycles", None),
         ("steps", "steps", None), ("time s", "seconds", ".3g"), ("limit s", "limit_s", "g"),
         ("energy", "energy_rel", ".2e"), ("limit", "energy_limit", "g"), ("peak RSS GB", "peak_rss_GB", ".3g"),
         ("status", "status", None)],
    )  # fmt: skip
    lines += [
        "",
        "Projected times are linear in the cycles from the longest run made; its energy error and peak memory are "
        "those of that run. Reference energies: the Masing closed form, or (out of phase) the reference run of the "
        "first three cycles, whose last cycle repeats.",
    ]
    return "\n".join(lines) + "\n"


def _ratio_text(ratio):
    parts = [f"On `{ratio['scene']}` the default takes {ratio['default_ms']:.3g} ms per step."]
    if ratio["low"]:
        label, value = ratio["low"]
        parts.append(
            f"The most resolved baseline it equals or beats on every error, {label}, takes **{value:.3g} x** as long."
        )
    else:
        parts.append("The default is less accurate than every baseline measured on some error.")
    if ratio["high"]:
        label, value = ratio["high"]
        parts.append(
            f"The cheapest baseline that equals or beats it on every error, {label}, takes {value:.3g} x as long."
        )
    else:
        parts.append("No baseline measured reaches the default's errors: the ratio at equal error is larger still.")
    return " ".join(parts)


def write_md(report, path, png_name):
    path.write_text(markdown(report, png_name))
    return path


# -- Command line -------------------------------------------------------------------------------


def add_arguments(parser):
    """Options of the script."""
    parser.add_argument("--out", default="results", metavar="DIR", help="directory of the outputs (default: results)")
    parser.add_argument("--quick", action="store_true", help="small scenes and few configurations: a smoke test")
    parser.add_argument(
        "--repeats", type=int, default=None, help="timed runs per configuration (default 3; 1 with --quick)"
    )
    parser.add_argument(
        "--long-timeout",
        type=float,
        default=None,
        metavar="SECONDS",
        help="longest long run (default 60; 20 with --quick)",
    )
    parser.add_argument(
        "--any-threads",
        action="store_true",
        help="time with the BLAS threads as they are (default: rerun with one thread)",
    )
    return parser


def run(args):
    """Run the benchmark as `args` say; write the CSV, PNG and MD; return the exit code."""
    if not args.any_threads and any(os.environ.get(name) != "1" for name in harness.ONE_THREAD):
        command = [sys.executable, str(Path(__file__).resolve()), *_argv(args)]
        return subprocess.call(command, env=os.environ | harness.ONE_THREAD)
    repeats = args.repeats if args.repeats is not None else (1 if args.quick else 3)
    timeout = args.long_timeout if args.long_timeout is not None else (20.0 if args.quick else 60.0)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    log = lambda message: print(message, file=sys.stderr, flush=True)  # noqa: E731
    report = harness.benchmark(args.quick, repeats, timeout, timeout / 3, log)
    stem = out / "speed_vs_error"
    written = [
        write_csv(report["rows"], stem.with_suffix(".csv")),
        write_png(report["rows"], stem.with_suffix(".png")),
        write_md(report, stem.with_suffix(".md"), stem.with_suffix(".png").name),
    ]
    for path in written:
        print(path)
    return 0


def _argv(args):
    argv = ["--out", str(args.out), "--any-threads"]
    argv += ["--quick"] if args.quick else []
    argv += [] if args.repeats is None else ["--repeats", str(args.repeats)]
    return argv + ([] if args.long_timeout is None else ["--long-timeout", str(args.long_timeout)])


def main(argv=None):
    """``python benchmarks/speed_vs_error.py [options]``; returns the exit code."""
    parser = add_arguments(argparse.ArgumentParser(description=__doc__.splitlines()[0]))
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
