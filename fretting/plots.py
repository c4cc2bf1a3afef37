"""Figures of a result: traction snapshots, slip, the Q - delta_Q loop and the energy per cycle.

Each function draws on `ax`, or on the axes of a new pyplot figure when `ax` is None, and
returns the axes; none shows or saves a figure.
"""

import numpy as np
from matplotlib.ticker import MaxNLocator

__all__ = ["cycle_energy", "hysteresis", "slip", "snapshot_steps", "traction"]

#: Part of the contact, in |x - centre| / a, whose friction limit sets the traction axis: the
#: pressure of a sharp flat punch is unbounded at the edges.
INNER = 0.95


def snapshot_steps(result):
    """Steps worth a snapshot: those of the extreme values of Q and sigma, and the last one.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.simulate`.

    Returns
    -------
    ndarray of int
        Increasing steps; step 0, the starting state, only when it is the only one.
    """
    loads = [result.Q.values, result.sigma.values]
    steps = np.unique([f(load) for load in loads for f in (np.argmax, np.argmin)] + [result.sizes["step"] - 1])
    return steps[steps > 0] if steps.size > 1 else steps


def traction(result, steps=None, ax=None):
    """Shear traction ``q / (f p0)`` against ``x / a`` at `steps`, the stick zones shaded.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.simulate`.
    steps : sequence of int, optional
        Steps to draw; `snapshot_steps` when omitted.
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
    for step in _steps(result, steps):
        (line,) = ax.plot(t, result.q.values[step] / fp0, label=_label(result, step))
        for start, end in zip(result.stick_start.values[step], result.stick_end.values[step], strict=True):
            if np.isfinite(start):
                ax.axvspan(*_position(result, np.array([start, end])), color=line.get_color(), alpha=0.12, linewidth=0)
    span = 1.1 * limit[np.abs(t) <= INNER].max()
    ax.set(
        xlim=(-1, 1), ylim=(-span, span), xlabel="$x / a$", ylabel="$q / (f p_0)$", title="shear traction, stick shaded"
    )
    ax.legend(fontsize="small")
    return ax


def slip(result, steps=None, ax=None):
    """Accumulated slip [um] against ``x / a`` at `steps` (`snapshot_steps` when omitted); returns the axes."""
    ax = _axes(ax)
    for step in _steps(result, steps):
        ax.plot(_position(result), result.slip.values[step] * 1e6, label=_label(result, step))
    ax.axhline(0, color="0.5", linewidth=0.8)
    ax.set(xlim=(-1, 1), xlabel="$x / a$", ylabel="slip [µm]", title="slip accumulated since the contact formed")
    ax.legend(fontsize="small")
    return ax


def hysteresis(result, ax=None):
    """The loop of ``Q / (f P)`` against ``delta_Q`` [um], the slip part of the displacement conjugate to Q."""
    ax = _axes(ax)
    ax.plot(result.delta_Q.values * 1e6, result.Q.values / (result.attrs["f"] * result.attrs["P"]), linewidth=1)
    ax.set(xlabel="$\\delta_Q$ [µm]", ylabel="$Q / (f P)$", title="hysteresis loop")
    return ax


def cycle_energy(result, ax=None):
    """Energy dissipated in each load cycle [mJ/m]; the result must have cycles."""
    if "cycle_dissipation" not in result or result.cycle_dissipation.size == 0:
        raise ValueError("the result has no load cycles: its history counts none")
    ax = _axes(ax)
    energy = result.cycle_dissipation.values * 1e3
    ax.plot(np.arange(1, energy.size + 1), energy, marker="o")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set(xlabel="cycle", ylabel="dissipation [mJ/m]", ylim=(0, None), title="energy dissipated per cycle")
    return ax


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt  # only for callers who give no axes: pyplot picks a backend

        ax = plt.figure().add_subplot()
    return ax


def _steps(result, steps):
    return snapshot_steps(result) if steps is None else np.asarray(steps)


def _position(result, x=None):
    """``(x - centre) / a`` of the nodes, or of the positions `x` [m]."""
    x = result.x.values if x is None else x
    return (x - result.attrs["centre"]) / result.attrs["a"]


def _label(result, step):
    Q, sigma = float(result.Q[step]), float(result.sigma[step])
    return f"step {step}: $Q/(fP)$ = {Q / (result.attrs['f'] * result.attrs['P']):.2f}, " + (
        f"$\\sigma/(f p_0)$ = {sigma / (result.attrs['f'] * result.attrs['p0']):.2f}"
    )
