"""The command ``stress``: the field under the surface of a result, and fatigue criteria mapped over it."""

from pathlib import Path

import numpy as np
import xarray as xr

from fretting.analysis import nucleation
from fretting.analysis.fatigue import CRITERIA, Material, MaterialFileError, apply, hot_spot, line_method, point_method
from fretting.analysis.stress import BULK_STATES, COMPONENTS, field
from fretting.cli.common import at_least, figure_class, positive_number, saved
from fretting.results.io import ResultError, load, save

#: Default grid of `fretting stress`: points along x and in depth, the depth and the half-span in
#: half-widths a (two half-widths hold the peak shear under the contact and the edge gradients).
STRESS_NX, STRESS_NZ, STRESS_DEPTH, STRESS_SPAN = 201, 101, 2.0, 2.0

#: Criterion of `fretting stress --material` without --criterion: SWT needs only E and nu.
DEFAULT_CRITERION = "swt"


def add_parser(commands, common, figures):
    """The subcommand ``stress``."""
    stress = commands.add_parser(
        "stress", parents=[common, figures], help="write the stress field under the surface of a result (and a figure)"
    )
    stress.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    stress.add_argument("-o", "--output", metavar="OUT", help="field file (default: <result stem>_stress.h5 beside it)")
    stress.add_argument("--nx", type=at_least(2, int), default=STRESS_NX, help=f"points along x (default {STRESS_NX})")
    stress.add_argument("--nz", type=at_least(2, int), default=STRESS_NZ, help=f"depths (default {STRESS_NZ})")
    stress.add_argument(
        "--depth",
        type=positive_number,
        default=STRESS_DEPTH,
        help=f"largest depth, in half-widths a (default {STRESS_DEPTH:g})",
    )
    stress.add_argument(
        "--span",
        type=positive_number,
        default=STRESS_SPAN,
        help=f"x from centre - SPAN a to centre + SPAN a (default {STRESS_SPAN:g})",
    )
    stress.add_argument(
        "--step",
        type=at_least(0, int),
        nargs="+",
        help="recorded steps (default: those of the last load cycle recorded whole, from its starting state, "
        "else the last step)",
    )
    stress.add_argument(
        "--body", choices=("specimen", "pad"), default="specimen", help="body of the field (default: the specimen)"
    )
    stress.add_argument("--nu", type=float, help="Poisson's ratio (default: the nu the result records)")
    stress.add_argument(
        "--bulk-state",
        choices=tuple(state.replace(" ", "-") for state in BULK_STATES),
        default="plane-strain",
        help="state of the specimen's bulk stress: plane-strain (held across its width, the default) or "
        "plane-stress (free across it, as a bar in tension); the contact's field is in plane strain either way",
    )
    stress.add_argument(
        "--material",
        metavar="FILE",
        help="material file (TOML, keys of fretting.analysis.fatigue.Material): map fatigue criteria over the steps, "
        "taken as one cycle, and read them at the critical distance when it gives critical_distance",
    )
    stress.add_argument(
        "--criterion",
        nargs="+",
        choices=tuple(CRITERIA),
        help=f"criteria mapped with --material (default: {DEFAULT_CRITERION})",
    )
    stress.add_argument(
        "--figure",
        choices=(*COMPONENTS, *CRITERIA),
        help="also draw this component at the last step, or this criterion's map (with --material), "
        "as <OUT stem>_<name>.<format>",
    )
    stress.set_defaults(command=_stress, usage_error=stress.error)


def _stress(args):
    criteria = _stress_criteria(args)
    material = Material.from_file(args.material) if criteria else None
    result = load(args.file)
    a, centre = result.attrs["a"], result.attrs["centre"]
    x = centre + a * np.linspace(-args.span, args.span, args.nx)
    z = a * np.linspace(0.0, args.depth, args.nz)
    specimen = nucleation.specimen(result)
    body = specimen if args.body == "specimen" else 3 - specimen
    try:
        stresses = field(
            result,
            x,
            z,
            step=args.step or _last_cycle(result),
            body=body,
            nu=args.nu,
            bulk_state=args.bulk_state.replace("-", " "),
        )
    except ValueError as error:
        raise ResultError(f"{args.file}: {error}") from None
    written = xr.merge([stresses, *(_criterion_map(stresses, name, material, args.material) for name in criteria)])
    output = Path(args.output or Path(args.file).with_name(f"{Path(args.file).stem}_stress.h5"))
    save(written, output)
    print(
        f"{output}: {stresses.sizes['step']} steps, {stresses.sizes['z']} x {stresses.sizes['x']} points, "
        f"body {body} ({args.body}), "
        f"bulk stress in {stresses.attrs['bulk_state']}"
    )
    for name in criteria:
        print(_critical_distances(name, written[name]))
    if args.figure:
        Figure = figure_class()

        from fretting import plots

        figure = Figure(figsize=args.size, layout="constrained")
        plots.stress_map(written[args.figure], result, step=int(written.step[-1]), ax=figure.subplots())
        saved(figure, output.with_name(f"{output.stem}_{args.figure}"), args)


def _stress_criteria(args):
    """The criteria `fretting stress` maps: --criterion (default `DEFAULT_CRITERION`) and a --figure of one."""
    if args.material is None:
        if args.criterion or args.figure in CRITERIA:
            option = "--criterion" if args.criterion else f"--figure {args.figure}"
            args.usage_error(f"{option}: a criterion needs --material FILE (the material's constants)")
        return []
    criteria = list(dict.fromkeys(args.criterion or [DEFAULT_CRITERION]))
    return criteria + ([args.figure] if args.figure in CRITERIA and args.figure not in criteria else [])


def _criterion_map(stresses, name, material, path):
    """`fretting.analysis.fatigue.apply` over the field's steps, its variables renamed ``<name>`` (the parameter)
    and ``<name>_<variable>``, the parameter's attributes holding its critical distances."""
    try:
        maps = apply(stresses, name, material)
    except ValueError as error:  # a constant the criterion needs is missing from the file
        raise MaterialFileError(path, None, str(error).removeprefix("material: ")) from None
    maps = maps.rename({variable: name if variable == "parameter" else f"{name}_{variable}" for variable in maps})
    maps[name].attrs.update(_distances(maps[name], material, path))
    return maps


def _distances(parameter, material, path):
    """The surface hot spot, and the point and line methods below it (`fretting.analysis.fatigue`) when the material
    gives ``L``, as attributes [the parameter's units, m]."""
    value, x_hot = hot_spot(parameter)
    attributes = {"hot_spot": value, "x_hot": x_hot}
    L = material.critical_distance
    if L is None:
        return attributes
    try:
        point, line = point_method(parameter, L, x_hot=x_hot), line_method(parameter, L, x_hot=x_hot)
    except ValueError:
        reach = f"expected 2 L = {2 * L:.6g} m within the grid's depth {float(parameter.z[-1]):.6g} m (raise --depth)"
        raise MaterialFileError(path, "critical_distance", f"found {L!r} m, {reach}") from None
    return attributes | {"critical_distance": L, "point_method": point.value, "line_method": line.value}


def _critical_distances(name, parameter):
    """One line: a criterion's hot spot and its values at the critical distance."""
    attrs, units = parameter.attrs, parameter.attrs["units"]
    line = f"{name}: hot spot {attrs['hot_spot']:.6g} {units} at x = {attrs['x_hot']:.6g} m"
    if "critical_distance" not in attrs:
        return f"{line}; no critical distance (the material gives none)"
    return (
        f"{line}; point method (L/2 = {attrs['critical_distance'] / 2:.6g} m below it) "
        f"{attrs['point_method']:.6g} {units}; line method (mean over 2 L) {attrs['line_method']:.6g} {units}"
    )


def _last_cycle(result):
    """Steps of the last load cycle recorded whole, from its starting state; else the last step."""
    if "cycle_number" in result.dims and result.sizes["cycle_number"]:
        rows = nucleation.complete_cycles(result)[-1]
        if rows is not None:
            return result.step.values[rows].tolist()
    return [int(result.step[-1])]
