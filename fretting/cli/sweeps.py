"""The command ``sweep``, and ``info`` and ``plot`` of a sweep's dataset."""

import json
from pathlib import Path

import numpy as np

from fretting.cli.common import figure_class, progress_bar, saved
from fretting.loading.history_file import HistoryFileError
from fretting.studies import running
from fretting.studies.sweeps import (
    REGIMES,
    case_file,
    figures_for,
    keys,
    load_sweep,
    read_sweep,
    resolve_sweep,
    run_one,
    run_sweep,
    value_text,
)

#: The variables of a running-condition sweep that `fretting plot` maps over (delta*, P), with the boundary.
RUNNING_MAPS = ("cycle_regime", "energy_ratio")


def add_parser(commands, common):
    """The subcommand ``sweep``."""
    sweep = commands.add_parser(
        "sweep", parents=[common], help="run a sweep file on dask.distributed, or one case of it (job arrays)"
    )
    sweep.add_argument("file", metavar="SWEEP", help="sweep file (TOML), or the name of a shipped sweep")
    sweep.add_argument(
        "-o", "--output", metavar="OUT", help="dataset (default: results/<sweep stem>.h5); cases go to OUT.cases/"
    )
    how = sweep.add_mutually_exclusive_group()
    how.add_argument(
        "--scheduler",
        metavar="ADDR",
        help="dask scheduler address, e.g. tcp://host:8786 (default: a local cluster, one worker per core)",
    )
    how.add_argument(
        "--scheduler-file", metavar="FILE", help="file of a running dask scheduler (dask scheduler --scheduler-file)"
    )
    how.add_argument(
        "--case",
        type=int,
        metavar="K",
        help="run case K (from 0) alone, in this process, into OUT.cases/: a task of a job array "
        "(--case $SLURM_ARRAY_TASK_ID); then a sweep without --case joins the cases",
    )
    how.add_argument("--list-cases", action="store_true", help="list the cases: number, values, file in OUT.cases/")
    sweep.set_defaults(command=_sweep)


def _sweep(args):
    file = resolve_sweep(args.file)
    plan = read_sweep(file)
    output = Path(args.output) if args.output else Path("results") / f"{file.stem}.h5"
    cases = plan.cases()
    if args.list_cases:
        for k, values in enumerate(cases):
            print(f"{k}\t{_values(values)}\t{case_file(output, plan.base, plan.case(values))}")
        return
    if args.case is not None:
        if not 0 <= args.case < len(cases):
            expected = f"expected a case from 0 to {len(cases) - 1} (--list-cases lists them)"
            raise HistoryFileError(file, None, "--case", f"found {args.case}, {expected}")
        path, summary, ran = run_one(plan, args.case, output)
        regime = REGIMES[int(summary.regime)].replace("_", " ")
        again = "" if ran else " (its file was there: not run again)"
        print(f"{path}: case {args.case} of {len(cases)}, {_values(cases[args.case])}: {regime}{again}")
        return
    with progress_bar("case", args.interrupts) as progress:
        swept = run_sweep(plan, args.scheduler, output, scheduler_file=args.scheduler_file, progress=progress)
    dims = " x ".join(f"{key} ({len(values)})" for key, values in plan.grid.items())
    print(f"{output}: {swept.regime.size} cases over {dims}: {_regimes(swept)}")


def _regimes(cases):
    """The cases of the sweep dataset `cases` in each regime, e.g. ``0 stuck, 2 partial slip, 1 gross slip``."""
    counts = np.bincount(cases.regime.values.ravel(), minlength=len(REGIMES))
    return ", ".join(f"{count} {name.replace('_', ' ')}" for count, name in zip(counts, REGIMES, strict=True))


def _values(values):
    """The values of a case, ``key = value`` joined by commas (lists as JSON)."""
    return ", ".join(f"{key} = {json.dumps(value)}" for key, value in values.items())


def sweep_info(args):
    cases = load_sweep(args.file)
    attrs, names = cases.attrs, keys(cases)
    print(args.file)
    print(f"  {'history':<9} {attrs.get('history_file', '?')} (base sha256 {attrs.get('base_sha256', '?')})")
    for n, (dim, key) in enumerate(names.items()):
        units = cases[dim].attrs.get("units")
        shown = ", ".join(value_text(value) for value in cases[dim].values) + (f" [{units}]" if units else "")
        print(f"  {'grid' if n == 0 else '':<9} {key} ({cases.sizes[dim]}): {shown}")
    print(f"  {'cases':<9} {cases.regime.size}: {_regimes(cases)}")
    for n, (name, variable) in enumerate(cases.data_vars.items()):
        values = variable.values[np.isfinite(variable.values)]
        found = f"{values.min():.4g} to {values.max():.4g}" if values.size else "none"
        missing = variable.size - values.size
        what = f"{variable.attrs.get('long_name', name)} [{variable.attrs.get('units', '?')}]"
        print(f"  {'recorded' if n == 0 else '':<9} {name}: {what}: {found}" + (f" ({missing} NaN)" if missing else ""))
    print(f"  {'created':<9} {attrs.get('created', '?')}")


def sweep_plot(args):
    Figure = figure_class()

    cases = load_sweep(args.file)
    directory = Path(args.output) if args.output else Path(args.file).parent
    directory.mkdir(parents=True, exist_ok=True)
    for name, draw in figures_for(cases).items():
        figure = Figure(figsize=args.size, layout="constrained")
        draw(cases, ax=figure.subplots())
        saved(figure, directory / f"{Path(args.file).stem}_{name}", args)
    if running.running_dims(cases) is not None:  # a sweep over P and a displacement amplitude
        from fretting import plots

        mapped = running.running_cases(cases)
        for name in RUNNING_MAPS:
            figure = Figure(figsize=args.size, layout="constrained")
            plots.running_condition_map(mapped, name, ax=figure.subplots())
            saved(figure, directory / f"{Path(args.file).stem}_running_{name}", args)
