"""Figures of a result: snapshots along the contact, hysteresis loops, energy per cycle and its density.

Each function draws on `ax`, or on the axes of a new pyplot figure when `ax` is None, and
returns the axes; none shows or saves a figure. `FIGURES` names the figures that take
``(result, ax=None)``; `figures_for` says which of them a result can draw. Positions are
``x / a`` from the contact centre, tractions and stresses ``/ (f p0)``, loads ``Q / (f P)`` and
``sigma / (f p0)``; energies, energy densities and displacements keep their units. In the
figures of one curve per cycle, cycles whose curves are the same to the eye (`SAME_CURVE`) are
drawn once and named together in the legend (``cycle 2 (= 3, 4)``).
"""

import numpy as np
from matplotlib.ticker import MaxNLocator

from fretting.analysis import nucleation

__all__ = [
    "FIGURES",
    "accumulated_density",
    "contact_edges",
    "cycle_energy",
    "dissipation_density",
    "figures_for",
    "hysteresis",
    "loops",
    "peak_density",
    "sigma_loops",
    "slip",
    "slip_amplitude",
    "snapshot_steps",
    "stress_map",
    "surface_stress",
    "traction",
]

#: Part of the contact, in |x - centre| / a, whose friction limit sets the traction axis: the
#: pressure of a sharp flat punch is unbounded at the edges.
INNER = 0.95

#: Cycles from which per-cycle plots use logarithmic axes: a long run's early transient and
#: its steady state then share one figure.
LOG_CYCLES = 100

#: Axis label of ``delta_Q``: the slip part of the displacement conjugate to Q
#: (docs/theory/conventions.md#energy); the elastic part, linear in Q and defined in plane strain
#: only up to a datum, is left out.
DELTA_Q_LABEL = "slip part of the displacement, $\\delta_Q$ [µm]"

#: Contour levels of `stress_map`.
STRESS_LEVELS = 24

#: Cycles drawn by default in the figures that show one curve per cycle: enough to see a
#: transient settle, few enough to tell apart.
CURVES = 5

#: Curves of one figure closer than this fraction of the drawn range, in both coordinates at
#: every point, are one to the eye: drawn once, with one legend entry naming them all
#: (`_distinct`), rather than a curve hidden under another whose entry still shows.
SAME_CURVE = 1e-3


def snapshot_steps(result):
    """Recorded steps worth a snapshot: those of the extreme values of Q and sigma, and the last one.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation`.

    Returns
    -------
    ndarray of int
        Increasing step numbers (``result.step``, which are not the rows when only some steps are
        recorded); the first recorded step, the starting state, only when it is the only one.
    """
    loads = [result.Q.values, result.sigma.values]
    rows = np.unique([f(load) for load in loads for f in (np.argmax, np.argmin)] + [result.sizes["step"] - 1])
    return result.step.values[rows[rows > 0] if rows.size > 1 else rows]


def traction(result, steps=None, ax=None):
    """Shear traction ``q / (f p0)`` against ``x / a`` at `steps`, the stick zones shaded.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation`.
    steps : sequence of int, optional
        Step numbers to draw (recorded ones); `snapshot_steps` when omitted.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    t = _position(result)
    limit = result.p.values / result.attrs["p0"]  # f p / (f p0)
    for sign in (1, -1):
        ax.plot(t, sign * limit, color="0.5", linestyle="--", linewidth=0.8, label="$\\pm f p$" if sign > 0 else None)
    fp0 = result.attrs["f"] * result.attrs["p0"]
    for row in _rows(result, steps):
        (line,) = ax.plot(t, result.q.values[row] / fp0, label=_label(result, row))
        if "p_step" in result:  # a varying P: the limit of this step
            at = result.p_step.values[row] / result.attrs["p0"]
            ax.plot(t, at, t, -at, color=line.get_color(), linestyle=":", linewidth=0.8)
        for start, end in zip(result.stick_start.values[row], result.stick_end.values[row], strict=True):
            if np.isfinite(start):
                ax.axvspan(*_position(result, np.array([start, end])), color=line.get_color(), alpha=0.12, linewidth=0)
    limits = result.p_step.values / result.attrs["p0"] if "p_step" in result else limit
    reach = max(1.0, float(np.abs(t).max()))  # the nodes of a varying P span its largest contact
    span = 1.1 * limits[..., np.abs(t) <= INNER * reach].max()
    ax.set(
        xlim=(-reach, reach),
        ylim=(-span, span),
        xlabel="$x / a$",
        ylabel="$q / (f p_0)$",
        title="shear traction, stick shaded",
    )
    ax.legend(fontsize="small")
    return ax


def slip(result, steps=None, ax=None):
    """Accumulated slip [um] against ``x / a`` at `steps` (`snapshot_steps` when omitted); returns the axes."""
    ax = _axes(ax)
    for row in _rows(result, steps):
        ax.plot(_position(result), result.slip.values[row] * 1e6, label=_label(result, row))
    ax.axhline(0, color="0.5", linewidth=0.8)
    ax.set(xlim=(-1, 1), xlabel="$x / a$", ylabel="slip [µm]", title="slip accumulated since the contact formed")
    ax.legend(fontsize="small")
    return ax


def hysteresis(result, ax=None):
    """The loop of ``Q / (f P)`` against ``delta_Q`` [um], the slip part of the displacement conjugate to Q."""
    ax = _axes(ax)
    ax.plot(result.delta_Q.values * 1e6, result.Q.values / (result.attrs["f"] * result.attrs["P"]), linewidth=1)
    ax.set(xlabel=DELTA_Q_LABEL, ylabel="$Q / (f P)$", title="hysteresis loop of Q")
    return ax


def cycle_energy(result, ax=None):
    """Energy dissipated in each load cycle [mJ/m]; logarithmic axes from `LOG_CYCLES` cycles on.

    Raises
    ------
    ValueError
        When the result has no load cycles.
    """
    energy = _require_cycles(result).cycle_dissipation.values * 1e3
    ax = _axes(ax)
    number = result.cycle_number.values
    if number.size >= LOG_CYCLES:
        ax.loglog(number, energy, linewidth=1)
    else:
        ax.plot(number, energy, marker="o")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylim(0, None)
    ax.set(xlabel="cycle", ylabel="dissipation $E_d$ [mJ/m]", title="energy dissipated per cycle")
    return ax


def loops(result, cycles=None, ax=None):
    """Hysteresis loops ``Q / (f P)`` against ``delta_Q`` [um] of several cycles recorded whole.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` with load cycles.
    cycles : sequence of int, optional
        Cycle numbers; by default up to `CURVES` of the cycles recorded whole, from the first
        to the last.
    ax : matplotlib.axes.Axes, optional
    """
    fP = result.attrs["f"] * result.attrs["P"]
    ax, both = _loops(result, cycles, ax, "delta_Q", 1e6, result.Q.values / fP)
    area = "the part of the energy per cycle that Q does" if both else "energy per cycle"
    ax.set(xlabel=DELTA_Q_LABEL, ylabel="$Q / (f P)$", title=f"hysteresis loops of Q (area: {area})")
    return ax


def sigma_loops(result, cycles=None, ax=None):
    """Loops ``sigma / (f p0)`` against ``delta_sigma / a`` [um] of several cycles recorded whole (as `loops`)."""
    fp0 = result.attrs["f"] * result.attrs["p0"]
    ax, both = _loops(result, cycles, ax, "delta_sigma", 1e6 / result.attrs["a"], result.sigma.values / fp0)
    area = "the part of the energy per cycle that sigma does" if both else "energy per cycle"
    ax.set(
        xlabel="$\\delta_\\sigma / a$ [µm]",
        ylabel="$\\sigma / (f p_0)$",
        title=f"bulk-tension loops (area times a: {area})",
    )
    return ax


def dissipation_density(result, cycles=None, ax=None):
    """Energy dissipated per unit area in each of several cycles, ``w(x)`` [J/m^2], against ``x / a``.

    `cycles` defaults to up to `CURVES` cycles from the first to the last (log-spaced).
    """
    w = nucleation.dissipation_density(result)
    ax = _per_cycle_curves(result, w, cycles, ax, 1.0)
    ax.set(xlabel="$x / a$", ylabel="$w$ [J/m²]", title="energy dissipated per unit area in the cycle")
    return ax


def accumulated_density(result, cycles=None, ax=None):
    """Energy dissipated per unit area accumulated up to several cycles [J/m^2], against ``x / a``.

    `cycles` defaults to up to `CURVES` cycles from the first to the last (log-spaced).
    """
    accumulated = nucleation.accumulated_dissipation_density(result)
    ax = _per_cycle_curves(result, accumulated, cycles, ax, 1.0, label="after cycle {}")
    ax.set(xlabel="$x / a$", ylabel="$\\sum_k w_k$ [J/m²]", title="accumulated dissipated energy density")
    return ax


def slip_amplitude(result, cycles=None, ax=None):
    """Slip amplitude (half the slip range of the cycle) [um] of several cycles, against ``x / a``."""
    delta = nucleation.slip_amplitude(result)
    ax = _per_cycle_curves(result, delta, cycles, ax, 1e6)
    ax.set(xlabel="$x / a$", ylabel="slip amplitude $\\delta$ [µm]", title="slip amplitude in the cycle")
    return ax


def peak_density(result, ax=None):
    """Peak of ``w(x)`` in each cycle [J/m^2] against the cycle, with its position ``x / a`` (right axis)."""
    peak = nucleation.peak_dissipation_density(_require_cycles(result))
    ax = _axes(ax)
    number = result.cycle_number.values
    log = number.size >= LOG_CYCLES
    (line,) = ax.plot(number, peak.w_max.values, marker=None if log else "o", label="$w_{max}$")
    ax.set(xlabel="cycle", ylabel="$w_{max}$ [J/m²]", title="peak dissipated energy density per cycle")
    position = ax.twinx()
    position.plot(number, _position(result, peak.x_w_max.values), color="0.4", linestyle=":", label="position")
    position.set(ylabel="position of $w_{max}$, $x / a$", ylim=(-1.05, 1.05))
    if log:
        ax.set_xscale("log")
        ax.set_yscale("log")
    else:
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylim(0, None)
    ax.legend(handles=[line, *position.get_lines()], fontsize="small")
    return ax


def contact_edges(result, ax=None):
    """The contact edges ``+-a / a_formed`` and the stick zones' ends against the step, where ``P`` varies.

    Parameters
    ----------
    result : xarray.Dataset
        A result of a history of ``P`` (it has ``a``).
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    if "a" not in result:
        raise ValueError("the result has no contact half-width a: its history does not vary P")
    ax = _axes(ax)
    steps, edge = result.step.values, result.a.values / result.attrs["a"]
    ax.plot(steps, edge, steps, -edge, color="k", linewidth=1)
    for name in ("stick_start", "stick_end"):
        ends = _position(result, result[name].values)
        ax.plot(np.repeat(steps, ends.shape[1]), ends.ravel(), ".", color="C0", markersize=2)
    ax.set(xlabel="step", ylabel="$x / a$ (contact formed)", title="contact edges (lines) and stick-zone ends (dots)")
    return ax


def surface_stress(result, steps=None, ax=None, body=None, bulk=None):
    """Surface direct stress ``sigma_xx / (f p0)`` of `body` against ``x / a`` at `steps`.

    See `fretting.analysis.nucleation.surface_stress` for `body` and `bulk`: by default the
    specimen, with its bulk stress. `steps` default to `snapshot_steps`.
    """
    ax = _axes(ax)
    field = nucleation.surface_stress(result, body, bulk)
    stress = field.values / (result.attrs["f"] * result.attrs["p0"])
    t = _position(result)
    for row in _rows(result, steps):
        ax.plot(t, stress[row], label=_label(result, row))
    ax.axhline(0, color="0.5", linewidth=0.8)
    ax.set(
        xlim=(-1, 1),
        xlabel="$x / a$",
        ylabel="$\\sigma_{xx} / (f p_0)$",
        title=f"surface direct stress, {field.role} (body {field.body}, traction {'+q' if field.body == 1 else '-q'})",
    )
    ax.legend(fontsize="small")
    return ax


def stress_map(data, result, step=None, ax=None, levels=STRESS_LEVELS):
    """Filled contours of a field under the surface against ``x / a`` and depth ``z / a``, at one step.

    The contact ``|x - centre| <= a`` is drawn along the surface and, when the step is known,
    its stick zones over it (``stick_start``, ``stick_end`` of `result`).

    Parameters
    ----------
    data : xarray.DataArray
        A variable on dims (z, x) or (step, z, x), ``z`` the depth [m] (a component of
        `fretting.analysis.stress.field`, or any map on its points, e.g. a fatigue parameter); its
        ``long_name`` and ``units`` label the colour bar.
    result : xarray.Dataset
        The result the field was computed from: its ``a``, ``centre`` and stick zones.
    step : int, optional
        Step to draw when `data` has a step dimension (default: its last); for data without
        one, the step whose stick zones to mark (None: none marked).
    ax : matplotlib.axes.Axes, optional
    levels : int
        Number of contour levels.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    if "step" in data.dims:
        step = int(data.step[-1]) if step is None else step
        data = data.sel(step=step)
    a = result.attrs["a"]
    filled = ax.contourf(_position(result, data.x.values), data.z.values / a, data.transpose("z", "x").values, levels)
    label = data.attrs.get("long_name", data.name or "")
    ax.figure.colorbar(filled, ax=ax, label=f"{label} [{data.attrs.get('units', '-')}]")
    ax.plot([-1, 1], [0, 0], color="black", linewidth=4, solid_capstyle="butt", clip_on=False, label="contact")
    if step is not None:
        row = _rows(result, [step])[0]
        ends = zip(result.stick_start.values[row], result.stick_end.values[row], strict=True)
        for k, (start, end) in enumerate((s, e) for s, e in ends if np.isfinite(s)):
            ax.plot(
                _position(result, np.array([start, end])),
                [0, 0],
                color="white",
                linewidth=2,
                clip_on=False,
                label="stick zone" if k == 0 else None,
            )
    ax.invert_yaxis()
    ax.set(xlabel="$x / a$", ylabel="depth $z / a$", title=f"{data.name}" + ("" if step is None else f", step {step}"))
    ax.legend(fontsize="small", loc="lower right")
    return ax


#: The figures that take ``(result, ax=None)``, by name (the command line's file suffixes).
FIGURES = {
    "traction": traction,
    "slip": slip,
    "surface_stress": surface_stress,
    "hysteresis": hysteresis,
    "loops": loops,
    "sigma_loops": sigma_loops,
    "energy": cycle_energy,
    "dissipation_density": dissipation_density,
    "accumulated_density": accumulated_density,
    "slip_amplitude": slip_amplitude,
    "peak_density": peak_density,
    "contact_edges": contact_edges,
}


def figures_for(result):
    """Names of the `FIGURES` that `result` can draw, in the order of `FIGURES`.

    Snapshots always, and the whole path's loop of Q unless Q is zero throughout; per-cycle
    figures when the history counts cycles: the energy per cycle always, the loops of Q (of
    sigma) when Q (sigma) varies in a cycle recorded whole, densities and slip amplitudes when
    they are known for a cycle and stored for every cycle (not for a long run whose
    ``cycle_fields`` policy stored them for some cycles: `fretting.analysis.nucleation` refuses
    those, and the result's ``w_total`` and ``*_max`` fields hold what every cycle adds up to).
    """
    names = {"traction", "slip", "surface_stress"} | ({"contact_edges"} if "a" in result else set())
    if np.any(result.Q.values != 0):
        names.add("hysteresis")
    if "cycle_number" in result.dims and result.sizes["cycle_number"]:
        names.add("energy")
        whole = [rows for rows in nucleation.complete_cycles(result) if rows is not None]
        for load, name in (("Q", "loops"), ("sigma", "sigma_loops")):
            if any(np.ptp(result[load].values[rows]) > 0 for rows in whole):
                names.add(name)
        if "field_cycle" not in result.dims and not np.isnan(nucleation.dissipation_density(result).values).all():
            names |= {"dissipation_density", "accumulated_density", "slip_amplitude", "peak_density"}
    return [name for name in FIGURES if name in names]


def _require_cycles(result):
    if "cycle_number" not in result.dims or result.sizes["cycle_number"] == 0:
        raise ValueError("the result has no load cycles: its history counts none")
    return result


def _spread(numbers, count=CURVES):
    """Up to `count` of `numbers` (sorted), the first and the last among them, log-spaced by position."""
    numbers = np.asarray(numbers)
    if numbers.size <= count:
        return numbers
    positions = np.unique(np.round(np.geomspace(1, numbers.size, count)).astype(np.int64) - 1)
    return numbers[positions]


def _loops(result, cycles, ax, displacement, scale, load):
    """Draw `load` against ``scale`` times the `displacement` over the chosen cycles.

    Returns the axes and whether both Q and sigma vary in a drawn cycle: then a loop's area is
    only its load's part of the energy dissipated.
    """
    rows = dict(zip(_require_cycles(result).cycle_number.values, nucleation.complete_cycles(result), strict=True))
    whole = [number for number, row in rows.items() if row is not None]
    if not whole:
        raise ValueError("no load cycle was recorded whole: record every step of at least one cycle")
    chosen = _spread(whole) if cycles is None else np.asarray(cycles)
    ax = _axes(ax)
    values = result[displacement].values * scale
    for number in chosen:
        if rows.get(int(number)) is None:
            raise ValueError(f"cycle {number} was not recorded whole; cycles recorded whole: {whole}")
    curves = [(values[rows[int(n)]], load[rows[int(n)]]) for n in chosen]
    for (x, y), numbers in _distinct(curves, chosen):
        ax.plot(x, y, linewidth=1, label=_cycles_label("cycle {}", numbers))
    ax.legend(fontsize="small")
    both = any(
        np.ptp(result.Q.values[rows[int(n)]]) > 0 and np.ptp(result.sigma.values[rows[int(n)]]) > 0 for n in chosen
    )
    return ax, both


def _per_cycle_curves(result, field, cycles, ax, scale, label="cycle {}"):
    """One curve of the (cycle_number, x) `field` per chosen cycle, against ``x / a``."""
    known = field.cycle_number.values[~np.isnan(field.values).all(axis=1)]
    chosen = _spread(known) if cycles is None else np.asarray(cycles)
    ax = _axes(ax)
    t = _position(result)
    curves = [(t, field.sel(cycle_number=number).values * scale) for number in chosen]
    for (x, y), numbers in _distinct(curves, chosen):
        ax.plot(x, y, label=_cycles_label(label, numbers))
    ax.set_xlim(-1, 1)
    ax.legend(fontsize="small")
    return ax


def _distinct(curves, numbers):
    """``((x, y), [numbers])`` of each distinct curve of `curves` (pairs of arrays), in order, with
    the `numbers` of the curves it stands for: a curve within `SAME_CURVE` of the drawn range of one
    before it, in both coordinates at every point, joins that one (it would be hidden under it)."""
    finite = [np.concatenate([c[k][np.isfinite(c[k])] for c in curves]) for k in (0, 1)]
    span = [np.ptp(v) if v.size else 0.0 for v in finite]
    kept = []
    for curve, number in zip(curves, numbers, strict=True):
        for other, joined in kept:
            if all(_within(curve[k], other[k], SAME_CURVE * span[k]) for k in (0, 1)):
                joined.append(number)
                break
        else:
            kept.append((curve, [number]))
    return kept


def _within(a, b, tolerance):
    """True if the arrays `a` and `b` have one shape and differ by at most `tolerance` (NaN where both are)."""
    if a.shape != b.shape:
        return False
    same_nan = np.isnan(a) == np.isnan(b)
    return bool(same_nan.all() and np.all(np.abs(a - b)[~np.isnan(a)] <= tolerance))


def _cycles_label(label, numbers):
    """`label` (a format of one cycle number) of the first of `numbers`, naming the others drawn with it."""
    first = label.format(numbers[0])
    return first if len(numbers) == 1 else f"{first} (= {', '.join(map(str, numbers[1:]))})"


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt  # only for callers who give no axes: pyplot picks a backend

        ax = plt.figure().add_subplot()
    return ax


def _rows(result, steps):
    """Rows of the recorded step numbers `steps` (`snapshot_steps` when None)."""
    steps = snapshot_steps(result) if steps is None else np.asarray(steps, dtype=np.int64)
    rows = np.searchsorted(result.step.values, steps)
    missing = steps[
        (rows >= result.sizes["step"]) | (result.step.values[np.minimum(rows, result.sizes["step"] - 1)] != steps)
    ]
    if missing.size:
        raise ValueError(f"steps {missing.tolist()} are not recorded in the result")
    return rows


def _position(result, x=None):
    """``(x - centre) / a`` of the nodes, or of the positions `x` [m]."""
    x = result.x.values if x is None else x
    return (x - result.attrs["centre"]) / result.attrs["a"]


def _label(result, row):
    """Legend of the recorded `row`: its step number (not the row) and loads."""
    Q, sigma = float(result.Q[row]), float(result.sigma[row])
    P = float(result.P[row]) if "P" in result else result.attrs["P"]  # a varying P: that of the step
    return f"step {int(result.step[row])}: $Q/(fP)$ = {Q / (result.attrs['f'] * P):.2f}, " + (
        f"$\\sigma/(f p_0)$ = {sigma / (result.attrs['f'] * result.attrs['p0']):.2f}"
    )
