"""Figures of fretting-fatigue maps (`fretting.studies.maps`): the nucleation boundary and life against contact size.

Each function draws on a matplotlib ``Axes`` and returns it, with its axes labelled in units; save the figure
as svg or pdf for a vector file (``figure.savefig("map.pdf")``). matplotlib is imported by the caller.
"""

import numpy as np

__all__ = ["life_against_size", "nucleation_boundary"]


def nucleation_boundary(boundary, ax, fP=None):
    """The boundary of `fretting.studies.maps.nucleation_boundary`: threshold ``Q_a`` [kN/m] against ``sigma_a`` [MPa].

    Parameters
    ----------
    boundary : xarray.Dataset
        A result of `fretting.studies.maps.nucleation_boundary`.
    ax : matplotlib.axes.Axes
    fP : float, optional
        ``f P`` [N/m]: drawn as the gross-slip limit of ``Q_a``.

    Points whose target is exceeded over the whole bracket are drawn at its low end, those never reached at its
    high end, as open markers.
    """
    sigma = boundary.sigma_amplitude.values / 1e6
    Q = boundary.Q_threshold.values / 1e3
    low, high = (end / 1e3 for end in boundary.attrs["bracket"])
    found = boundary.side.values == 0
    ax.plot(Q[found], sigma[found], "o-", color="C0", label="threshold")
    for side, at, text in ((1, low, "above target over the bracket"), (-1, high, "below target over the bracket")):
        chosen = boundary.side.values == side
        if chosen.any():
            ax.plot(
                np.full(chosen.sum(), at), sigma[chosen], "o", mfc="none", color="C1" if side > 0 else "C2", label=text
            )
    if fP is not None:
        ax.axvline(fP / 1e3, color="0.4", ls="--", lw=1, label="gross slip, $Q_a = fP$")
    ax.set_xlabel("shear force amplitude $Q_a$ [kN/m]")
    ax.set_ylabel(r"bulk stress amplitude $\sigma_a$ [MPa]")
    ax.set_title(f"{boundary.attrs['criterion']} at {boundary.attrs['at']}: {boundary.attrs['target']}", fontsize=10)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    return ax


def life_against_size(lives, ax, size_label="contact half-width $a$ [mm]", size_scale=1e3, by="a"):
    """Life of `fretting.studies.maps.life_against_size` against the contact size, with the run-out line.

    Parameters
    ----------
    lives : xarray.Dataset
        A result of `fretting.studies.maps.life_against_size`.
    ax : matplotlib.axes.Axes
    size_label : str
        The label of the size axis, with its units.
    size_scale : float
        Factor from the size's SI units to those of the label (1e3: m to mm).
    by : {"a", "size"}
        The contact half-width of each run, or the values given to the scene.

    Lives at or beyond the run-out are drawn at the run-out line as open triangles (tests stopped unbroken).
    """
    size = (lives.a if by == "a" else lives["size"]).values * size_scale
    N = lives.N_f.values
    runout = lives.attrs["runout"]
    out = lives.run_out.values
    ax.semilogy(size[~out], N[~out], "o", color="C0", label="predicted life")
    if out.any():
        ax.semilogy(size[out], np.full(out.sum(), runout), "^", mfc="none", color="C0", label="run-out")
    ax.axhline(runout, color="0.4", ls="--", lw=1, label=f"run-out, {runout:.3g} cycles")
    ax.set_xlabel(size_label)
    ax.set_ylabel("cycles to failure $N_f$")
    ax.set_title(f"{lives.attrs['criterion']} at {lives.attrs['at']}", fontsize=10)
    ax.legend(fontsize=8)
    return ax
