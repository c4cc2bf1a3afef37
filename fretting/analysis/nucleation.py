"""Crack-nucleation quantities of a result: dissipated energy density, surface stress, Ruiz and Fouvry.

Pure functions of a result of `fretting.engine.simulation`. Each returns DataArrays or Datasets whose
variables carry ``units``, ``long_name`` and ``definition`` (the formula and its source).

Conventions (those of docs/theory/conventions.md): the shear traction ``q`` acts on **body 1** (its
resultant is ``Q``) and ``-q`` on **body 2**; the slip ``s`` is that of body 2 relative to
body 1, so that ``q`` drives it. Eq (20) of the seed, with the surface strain of a half-plane,
then fixes the meaning of the differential bulk tension: ``sigma = sigma_b2 - sigma_b1``, the
bulk direct stress of body 2 minus that of body 1 (the fully stuck traction ``sigma x / (4
sqrt(a^2 - x^2))`` stretches body 1's surface by ``sigma / 2`` and compresses body 2's by as
much, which cancels the bulk strain mismatch ``sigma / (2 E_star)``).

The specimen is the body whose surface stress and Ruiz parameters are wanted: the result's
attribute ``specimen`` (`fretting.Contact`'s, 1 or 2), and body 2 for results written without
it (`SPECIMEN`: a specimen in bulk tension ``sigma`` under an unstressed pad). By default the
specimen carries the bulk stress and the pad none: body 2 ``sigma``, or body 1 ``-sigma``.

Per-cycle quantities follow the load cycles of the history (`cycle_number`). The engine tallies
``w``, ``slip_amplitude`` and, at each node, the peaks over the cycle's steps of the specimen's
``sigma_xx``, of ``|q|`` and of their product (``sigma_xx_peak``, ``q_peak``,
``sigma_xx_q_peak``) over every step, so they exist when only some steps are recorded; results
written before it did, and the surface stress of the pad or of another bulk stress, are served
by the recorded steps, for the cycles recorded whole.

References
----------
.. [1] Hills, Ramesh, Barber & Moore, Methods to solve half-plane partial slip contact
   problems (the seed paper).
.. [2] Johnson, Contact Mechanics, Cambridge University Press 1985, section 2.3 (surface
   stresses of a half-plane under distributed tractions).
.. [3] McEwen, Stresses in elastic cylinders in contact along a generatrix, Phil. Mag. 40
   (1949) 454-459.
.. [4] Ruiz, Boddington & Chen, An investigation of fatigue and fretting in a dovetail joint,
   Exp. Mech. 24 (1984) 208-217.
.. [5] Fouvry, Kapsa & Vincent, Quantification of fretting damage, Wear 200 (1996) 186-205.
.. [6] Fouvry, Duo & Perruchaut, A quantitative approach of Ti-6Al-4V fretting damage:
   friction, wear and crack nucleation, Wear 257 (2004) 916-929.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike
from scipy import sparse

from fretting.models.normal import CellSurfaceStress
from fretting.physics.closed_forms import masing_increment, masing_origin
from fretting.physics.contact import SPECIMEN
from fretting.physics.profiles import profile_class, recorded_profile
from fretting.physics.surface import ClosedFormSurfaceStress, SurfaceStress, bulk_stress, ellipse_stress
from fretting.results.loops import complete_cycles
from fretting.results.variables import CYCLE_PEAKS

__all__ = [
    "accumulated_dissipation_density",
    "body_bulk",
    "body_role",
    "complete_cycles",
    "cycles_to_nucleation",
    "dissipation_density",
    "elliptical_traction",
    "fouvry",
    "loop_work",
    "peak_dissipation_density",
    "per_cycle",
    "ruiz",
    "slip_amplitude",
    "specimen",
    "surface_stress",
]

#: Largest difference, relative to ``f p0``, between the recorded traction and the exact models'
#: elliptical reconstruction (`elliptical_traction`) for the reconstruction to be used: an exact
#: model's traction meets it to rounding (~1e-15), a discretised model's by its own error, far above this.
RECONSTRUCTION_RTOL = 1e-9

#: Largest change of ``w(x)`` between the last two cycles, relative to the peak of the last one,
#: for which the run counts as periodic and `cycles_to_nucleation` extrapolates beyond it. The
#: engine repeats periodic cycles bit for bit (change 0); 1e-3 leaves room for runs that settle slowly.
STEADY_RTOL = 1e-3

W_DEFINITION = (
    "w_k(x) = sum over the increments of cycle k of f p(x) |ds(x)|: energy dissipated per unit area "
    "of the interface in load cycle k (docs/theory/conventions.md#energy; the local form of the energy "
    "approach of Fouvry, Kapsa & Vincent, Wear 200 (1996) 186-205)"
)
DELTA_DEFINITION = (
    "delta_k(x) = (max s - min s) / 2 over load cycle k, its starting state included: the slip "
    "amplitude delta of Ruiz, Boddington & Chen, Exp. Mech. 24 (1984) 208-217"
)


def _attrs(units: str, long_name: str, definition: str) -> dict[str, str]:
    return {"units": units, "long_name": long_name, "definition": definition}


def _has_cycles(result: xr.Dataset) -> bool:
    return "cycle_number" in result.dims and result.sizes["cycle_number"] > 0


def _require_cycles(result: xr.Dataset) -> None:
    if not _has_cycles(result):
        raise ValueError("the result has no load cycles: its history counts none")


def _require_every_cycle(result: xr.Dataset, name: str) -> None:
    """Refuse to read the per-cycle field `name` of every cycle from a result that stores it only for
    the cycles its ``cycle_fields`` policy chose (dims field_cycle, x: `fretting.run_file`)."""
    if "field_cycle" in result.dims:
        raise ValueError(
            f"the result stores {name} only for the cycles {result.field_cycle.values.tolist()[:5]}... that its "
            f"cycle_fields policy ({result.attrs.get('cycle_fields')}) chose (result.{name}, dims field_cycle, x); "
            f"over every cycle it has w_total and the *_max fields, or run with cycle_fields='all'"
        )


def _refuse_varying_P(result: xr.Dataset, what: str) -> None:
    """Refuse `what` for a result of a varying ``P`` (it has ``p_step``): it would assume the contact formed."""
    if "p_step" in result:
        raise ValueError(f"{what} assumes the contact formed at the constant P; this result varies P (it has p_step)")


def dissipation_density(result: xr.Dataset) -> xr.DataArray:
    """Energy dissipated per unit area in each load cycle, ``w(x)`` [J/m^2].

    ``w_k(x) = sum_{increments of cycle k} f p(x) |ds(x)|`` (docs/theory/conventions.md#energy), whose
    integral over the contact is `cycle_dissipation`.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` with load cycles.

    Returns
    -------
    xarray.DataArray
        ``w``, dims (cycle_number, x): the engine's tally over every step when the result has
        it; otherwise from the recorded steps, NaN for cycles not recorded whole (ValueError for a
        result of a varying ``P``: the pressure changes within each increment, and for a result
        that stores ``w`` only for the cycles of its ``cycle_fields`` policy).
    """
    _require_cycles(result)
    _require_every_cycle(result, "w")
    if "w" in result:
        w = result.w.astype(np.float64)  # the engine keeps float32 rows; sums over many cycles need more
    else:
        _refuse_varying_P(result, "w from the recorded steps (the result has no tally w)")
        values = np.full((result.sizes["cycle_number"], result.sizes["x"]), np.nan)
        fp = result.attrs["f"] * result.p.values
        slip = result.slip.values
        for k, rows in enumerate(complete_cycles(result)):
            if rows is not None:
                values[k] = fp * np.abs(np.diff(slip[rows], axis=0)).sum(axis=0)
        w = xr.DataArray(values, coords={"cycle_number": result.cycle_number, "x": result.x})
    return w.rename("w").assign_attrs(
        _attrs("J/m^2", "energy dissipated per unit area in each load cycle", W_DEFINITION)
    )


def slip_amplitude(result: xr.Dataset) -> xr.DataArray:
    """Slip amplitude ``delta(x)`` [m] of each load cycle: half the range of the slip over it.

    The range includes the cycle's starting state. For a closed cycle this is the ``delta`` of
    Ruiz et al. (1984) [4]_.

    Returns
    -------
    xarray.DataArray
        ``slip_amplitude``, dims (cycle_number, x): the engine's tally when the result has it,
        otherwise from the recorded steps (NaN for cycles not recorded whole; ValueError for a
        result of a varying ``P``, whose recorded slip out of contact is that of the free surfaces).
    """
    _require_cycles(result)
    _require_every_cycle(result, "slip_amplitude")
    if "slip_amplitude" in result:
        delta = result.slip_amplitude.astype(np.float64)
    else:
        _refuse_varying_P(result, "the slip amplitude from the recorded steps (the result has no tally slip_amplitude)")
        values = np.full((result.sizes["cycle_number"], result.sizes["x"]), np.nan)
        slip = result.slip.values
        for k, rows in enumerate(complete_cycles(result)):
            if rows is not None:
                values[k] = (slip[rows].max(axis=0) - slip[rows].min(axis=0)) / 2
        delta = xr.DataArray(values, coords={"cycle_number": result.cycle_number, "x": result.x})
    attrs = _attrs("m", "slip amplitude: half the range of the slip over each load cycle", DELTA_DEFINITION)
    return delta.rename("slip_amplitude").assign_attrs(attrs)


def _largest(values: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Largest of each row of `values` (cycles, N) and its node `x` [m]; NaN for rows of NaN only."""
    valid = ~np.all(np.isnan(values), axis=1)
    at = np.zeros(values.shape[0], dtype=np.int64)
    at[valid] = np.nanargmax(values[valid], axis=1)
    return np.where(valid, values[np.arange(values.shape[0]), at], np.nan), np.where(valid, x[at], np.nan)


def _peak(field: xr.DataArray, name: str, units: str, long_name: str, definition: str) -> xr.Dataset:
    """Largest value over x of each row of `field` and its position, as a Dataset."""
    peak, x = _largest(field.values, field.x.values)
    coords = {"cycle_number": field.cycle_number}
    return xr.Dataset(
        {
            name: ("cycle_number", peak, _attrs(units, long_name, definition)),
            f"x_{name}": ("cycle_number", x, _attrs("m", f"position of {name}", f"argmax over the nodes of {name}")),
        },
        coords=coords,
    )


def peak_dissipation_density(result: xr.Dataset) -> xr.Dataset:
    """Peak of ``w(x)`` in each cycle [J/m^2] and its position [m] (at the nodes).

    Returns
    -------
    xarray.Dataset
        ``w_max`` and ``x_w_max``, dims (cycle_number,).
    """
    definition = "w_max = max over x of w_k(x), w the energy dissipated per unit area in cycle k"
    return _peak(
        dissipation_density(result), "w_max", "J/m^2", "peak dissipated energy density of the cycle", definition
    )


def accumulated_dissipation_density(result: xr.Dataset) -> xr.DataArray:
    """Energy dissipated per unit area over cycles 1 to k, ``sum_{j <= k} w_j(x)`` [J/m^2].

    Steps outside any cycle (the first loading ramp) are not included.

    Returns
    -------
    xarray.DataArray
        ``w_accumulated``, dims (cycle_number, x).
    """
    w = dissipation_density(result)
    definition = (
        "w_accumulated_k(x) = sum_{j <= k} w_j(x): the accumulated dissipated energy density of the "
        "energy approach (Fouvry, Duo & Perruchaut, Wear 257 (2004) 916-929), over the load cycles only"
    )
    attrs = _attrs("J/m^2", "energy dissipated per unit area, accumulated over the load cycles", definition)
    return w.cumsum("cycle_number").rename("w_accumulated").assign_attrs(attrs)


def fouvry(result: xr.Dataset) -> xr.Dataset:
    """Quantities of the accumulated dissipated energy approach, per cycle (Fouvry et al. [5]_, [6]_).

    The energy ratio ``A = E_d / (4 delta* Q*)`` of [5] is left out: in plane strain the
    displacement ``delta*`` needs a datum (docs/theory/conventions.md#energy), so ``A`` depends on it.

    Returns
    -------
    xarray.Dataset
        Dims (cycle_number,): ``E_d`` [J/m] energy dissipated in the cycle (`cycle_dissipation`),
        ``E_d_accumulated`` [J/m] its sum over cycles 1 to k, ``w_accumulated_max`` [J/m^2] the peak
        over x of the accumulated density and ``x_w_accumulated_max`` [m] its position.
    """
    _require_cycles(result)
    E_d = result.cycle_dissipation.values
    peak = _peak(
        accumulated_dissipation_density(result),
        "w_accumulated_max",
        "J/m^2",
        "peak accumulated dissipated energy density",
        "max over x of sum_{j <= k} w_j(x) (Fouvry, Duo & Perruchaut 2004)",
    )
    data = {
        "E_d": (
            "cycle_number",
            E_d,
            _attrs("J/m", "energy dissipated in the cycle", "E_d = int w dx = cycle_dissipation (Fouvry et al. 1996)"),
        ),
        "E_d_accumulated": (
            "cycle_number",
            np.cumsum(E_d),
            _attrs("J/m", "energy dissipated over cycles 1 to k", "sum_{j <= k} E_d,j (Fouvry et al. 2004)"),
        ),
    }
    return xr.Dataset(data, coords={"cycle_number": result.cycle_number}).merge(peak)


def specimen(result: xr.Dataset) -> int:
    """The body [1 or 2] that is the specimen: the result's ``specimen`` attribute, else `SPECIMEN` (body 2)."""
    return int(result.attrs.get("specimen", SPECIMEN))


def body_role(result: xr.Dataset, body: int | None) -> tuple[int, str]:
    """`body` [1 or 2], the specimen (`specimen`) when None, checked; and what it is, ``"specimen"`` or ``"pad"``.

    Raises
    ------
    ValueError
        When `body` is neither 1 nor 2.
    """
    body = specimen(result) if body is None else body
    if isinstance(body, bool) or body not in (1, 2):
        raise ValueError(f"body must be 1 (traction q) or 2 (traction -q), found {body!r}")
    return body, "specimen" if body == specimen(result) else "pad"


def body_bulk(result: xr.Dataset, body: int, bulk: ArrayLike | None = None) -> np.ndarray:
    """Bulk direct stress [Pa] of `body` at each recorded step, shape (step,), from body 1's `bulk` [Pa].

    `fretting.physics.surface.bulk_stress` with the result's ``sigma`` and specimen: None, the specimen
    carries the bulk stress and the pad none.
    """
    sigma = result.sigma.values
    bulk1 = None if bulk is None else np.broadcast_to(np.asarray(bulk, dtype=float), sigma.shape)
    return np.broadcast_to(bulk_stress(sigma, body, bulk1, specimen(result)), sigma.shape)


def surface_stress(result: xr.Dataset, body: int | None = None, bulk: ArrayLike | None = None) -> xr.DataArray:
    """Direct stress ``sigma_xx`` [Pa] along the surface of one body, at every recorded step.

    ``sigma_xx(x) = -(2/pi) PV int t_x(xi) / (x - xi) dxi - p(x) + sigma_b`` for a half-plane whose
    surface carries the shear traction ``t_x`` and the pressure ``p`` (Johnson 1985 [2]_, section
    2.3; plane strain), with ``t_x = q`` on body 1 and ``-q`` on body 2, and ``sigma_b`` the body's
    bulk stress (`fretting.physics.surface.SurfaceStress`, the formula the engine tallies the
    per-cycle peaks with). Check: a sliding Hertz contact, ``q = f p``, gives ``-p - 2 f p0 x / a``
    in body 1, a tension ``2 f p0`` at the trailing edge ``x = -a`` (McEwen 1949 [3]_).

    The traction of an exact model on a Hertz contact, a sum of elliptical loads
    (`elliptical_traction`), is integrated in closed form, exact at every node, stick ends included
    (`fretting.physics.surface.ellipse_stress`), as the engine's model integrates it.
    Otherwise the principal value is integrated exactly for ``sqrt(1 - t^2) q`` interpolated
    linearly between the nodes (`fretting.physics.surface.hilbert_matrix`), except next to a stick
    end (a node that stuck in the increment beside one that slipped) and next to a stick end an
    earlier turning point left inside the stick zone (a kink of the slip locked in there,
    `fretting.physics.surface.kinks`): there the stress has a square-root profile with a vertical
    tangent that no interpolation of the nodal traction resolves, and it is ``sigma / 2 - E_star
    ds/dx`` in body 1, from the slip fitted with its ``|x - c|^(3/2)``
    (`fretting.physics.surface.SurfaceStress.at_stick_ends`; accuracy, and the ends left unfitted:
    tests/analysis/test_nucleation.py, benchmarks/surface_stress.py, docs/guide/stress.md). For a result of a
    varying ``P``, ``q`` constant on each cell, with the pressure of each step
    (`fretting.models.normal.CellSurfaceStress`), the stick ends fitted among the cells in contact.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation`.
    body : {1, 2} or None
        1: the body on which the traction is ``q`` (resultant ``Q``); 2: the other one (``-q``);
        None: the specimen (`specimen`).
    bulk : float or array_like or None
        Bulk direct stress of body 1 [Pa], one value or one per recorded step. Body 2's is
        ``bulk + sigma``, since only the difference ``sigma = sigma_b2 - sigma_b1`` enters the
        contact. None: the specimen carries the bulk stress and the pad none (``-sigma`` when
        the specimen is body 1, else 0).

    Returns
    -------
    xarray.DataArray
        ``sigma_xx``, dims (step, x), at the nodes; attributes ``body`` and ``role``
        (``"specimen"`` or ``"pad"``).
    """
    body, role = body_role(result, body)
    bulk = body_bulk(result, body, bulk)[:, None]
    t = (result.x.values - result.attrs["centre"]) / result.attrs["a"]
    if "p_step" in result:  # a varying P: the equal cells of fretting.models.normal, the pressure of each step
        stress = _at_stick_ends(result, CellSurfaceStress(t), result.p_step.values, bulk, body)
    else:
        ellipses = elliptical_traction(result)
        if ellipses is None:
            stress = _at_stick_ends(result, SurfaceStress(t), result.p.values, bulk, body)
        else:
            widths, centres, loads = ellipses
            surface = ClosedFormSurfaceStress(loads @ ellipse_stress(t, widths[:, None], centres[:, None]))
            stress = surface(result.q.values, result.p.values, bulk, body)
    definition = (
        f"sigma_xx = -(2/pi) PV int t_x(xi)/(x - xi) dxi - p(x) + sigma_b, t_x = {'+q' if body == 1 else '-q'} "
        f"(body {body}), sigma_b its bulk stress (half-plane surface stress, Johnson 1985 section 2.3; "
        "sliding Hertz check: 2 f p0 at the trailing edge, McEwen 1949)"
    )
    attrs = _attrs("Pa", f"surface direct stress in the {role} (body {body})", definition)
    return xr.DataArray(
        stress, coords={"step": result.step, "x": result.x}, name="sigma_xx", attrs=attrs | {"body": body, "role": role}
    )


def _at_stick_ends(
    result: xr.Dataset, surface: SurfaceStress, p: np.ndarray, bulk: np.ndarray, body: int
) -> np.ndarray:
    """`surface` at each recorded step with its stick ends from the slip (`SurfaceStress.at_stick_ends`, as the
    engine tallies it), under the pressure `p` [Pa] (one row, or one per step); the steps of copied cycles,
    which repeat a slip and its stick, fitted once."""
    q, slip, sigma = result.q.values, result.slip.values, result.sigma.values
    stuck, modulus = result.stick.values.astype(bool), result.attrs["E_star"] / result.attrs["a"]
    fp0 = result.attrs["f"] * result.attrs["p0"]
    rows = np.broadcast_to(p, q.shape)
    shear, fitted = surface.away_from_ends(q, rows, slip, sigma[:, None], modulus), {}
    for k in range(q.shape[0]):
        key = (slip[k].tobytes(), stuck[k].tobytes(), sigma[k], surface.in_contact(rows[k]))
        if key not in fitted:
            fitted[key] = surface.stick_ends(rows[k], slip[k], stuck[k], sigma[k], modulus, fp0)
        nodes, values = fitted[key]
        shear[k, nodes] = values
    return ClosedFormSurfaceStress(shear)(q, p, bulk, body)


def _recorded_peaks(result: xr.Dataset, body: int, bulk: ArrayLike | None) -> dict[str, np.ndarray]:
    """`_cycle_peaks` from the recorded steps: NaN for the cycles not recorded whole (`complete_cycles`)."""
    peaks = np.full((len(CYCLE_PEAKS), result.sizes["cycle_number"], result.sizes["x"]), np.nan)
    stress, shear = surface_stress(result, body, bulk).values, np.abs(result.q.values)
    for k, rows in enumerate(complete_cycles(result)):
        if rows is not None:
            steps = slice(rows.start + 1, rows.stop)  # the steps of the cycle, not its starting state
            s, q = stress[steps], shear[steps]
            peaks[:, k] = s.max(axis=0), q.max(axis=0), (s * q).max(axis=0)
    return dict(zip(CYCLE_PEAKS, peaks, strict=True))


def _cycle_peaks(result: xr.Dataset, body: int, bulk: ArrayLike | None) -> dict[str, np.ndarray]:
    """Per cycle and node, the largest ``sigma_xx`` [Pa] of `body`, ``|q|`` [Pa] and ``sigma_xx |q|``
    [Pa^2] over the steps of the cycle (its increments, not its starting state).

    The engine's tallies over every step when the result has them (``sigma_xx`` only for the
    specimen with its bulk stress, which it tallies); otherwise, for results written without
    them or another body or bulk stress, from the recorded steps of the cycles recorded whole
    (NaN for the others).

    Returns
    -------
    dict
        ``sigma_xx_peak``, ``q_peak``, ``sigma_xx_q_peak``: ndarray, shape (cycles, N).
    """
    _require_every_cycle(result, "the peaks per cycle")
    tallied = {name: result[name].values.astype(np.float64) for name in CYCLE_PEAKS if name in result}
    if len(tallied) == len(CYCLE_PEAKS) and body == specimen(result) and bulk is None:
        return tallied
    return _recorded_peaks(result, body, bulk) | {name: tallied[name] for name in ("q_peak",) if name in tallied}


def ruiz(result: xr.Dataset, body: int | None = None, bulk: ArrayLike | None = None) -> xr.Dataset:
    """Ruiz parameters of each cycle, ``F1 = max(|q| delta)`` and ``F2 = max(sigma_xx |q| delta)``.

    Ruiz, Boddington & Chen (1984) [4]_: ``tau`` the surface shear traction, ``sigma_T`` the surface
    direct stress along the slip, ``delta`` the slip amplitude. Convention here: ``delta`` is the
    cycle's `slip_amplitude` at each node; ``|q|`` and ``sigma_xx`` (of `body`, see
    `surface_stress`) are those of each step of the cycle, and the maximum is over all its steps
    and the nodes: ``F1 = max_x delta(x) max_steps |q(x)|`` and ``F2 = max_x delta(x) max_steps
    sigma_xx(x) |q(x)|``, since ``delta >= 0``. The steps are every step of the run, from the
    engine's tally, when the result has it (``q_peak``, ``sigma_xx_q_peak``; ``sigma_xx`` of the
    specimen with its bulk stress only); otherwise, for results written without it or another
    body or bulk stress, the recorded steps of the cycles recorded whole (NaN for the others).
    ``F2`` is negative when the surface is in compression wherever it slips.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` with load cycles.
    body : {1, 2} or None
    bulk : float or array_like or None
        As for `surface_stress`: by default the specimen, with its bulk stress.

    Returns
    -------
    xarray.Dataset
        Dims (cycle_number,): ``F1`` [J/m^2], ``F2`` [Pa J/m^2] and their positions ``x_F1``,
        ``x_F2`` [m]; NaN where the cycle's peaks are not known.
    """
    _require_cycles(result)
    body, role = body_role(result, body)
    delta, peaks, x = slip_amplitude(result).values, _cycle_peaks(result, body, bulk), result.x.values
    F1, x_F1 = _largest(peaks["q_peak"] * delta, x)
    F2, x_F2 = _largest(peaks["sigma_xx_q_peak"] * delta, x)
    convention = "over every step of the cycle and the nodes, delta(x) its slip amplitude"
    attrs = {
        "F1": _attrs("J/m^2", "Ruiz parameter F1", f"F1 = max |q| delta {convention} (Ruiz et al. 1984)"),
        "F2": _attrs(
            "Pa J/m^2",
            "Ruiz parameter F2",
            f"F2 = max sigma_xx |q| delta, sigma_xx of the {role} (body {body}), {convention} (Ruiz et al. 1984)",
        ),
        "x_F1": _attrs("m", "position of F1", "node of the maximum F1"),
        "x_F2": _attrs("m", "position of F2", "node of the maximum F2"),
    }
    out = {"F1": F1, "F2": F2, "x_F1": x_F1, "x_F2": x_F2}
    data = {name: ("cycle_number", values, attrs[name]) for name, values in out.items()}
    return xr.Dataset(data, coords={"cycle_number": result.cycle_number}, attrs={"body": body, "role": role})


def cycles_to_nucleation(result: xr.Dataset, w_critical: float, steady_rtol: float = STEADY_RTOL) -> xr.Dataset:
    """Cycles until the peak accumulated dissipated energy density reaches `w_critical`.

    Energy approach (Fouvry et al. 2004 [6]_): a crack nucleates where ``sum_k w_k(x)`` first
    reaches a critical density ``w_c`` of the material. Between cycle ends the accumulated density
    at each node is interpolated linearly (a fractional cycle count); ``N_i`` is the least count
    over the nodes, ``x_i`` the node. When no node reaches ``w_c`` within the run and the last two
    cycles dissipate the same ``w(x)`` (to `steady_rtol` of its peak: a periodic steady state),
    each node's density is extrapolated linearly with the last cycle's ``w(x)`` per cycle.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` with load cycles.
    w_critical : float
        Critical dissipated energy density [J/m^2], > 0.
    steady_rtol : float
        Largest change of ``w(x)`` between the last two cycles, relative to the peak of the last,
        that counts as periodic.

    Returns
    -------
    xarray.Dataset
        Scalars ``N_i`` (inf when the steady cycle dissipates nothing) and ``x_i`` [m];
        attribute ``method``: "interpolated" or "extrapolated".

    Raises
    ------
    ValueError
        When the density is not reached within the run and the run does not end in a
        periodic state (or has fewer than two cycles), or a cycle's ``w`` is unknown.
    """
    if not np.isfinite(w_critical) or w_critical <= 0:
        raise ValueError(f"w_critical must be a number > 0 [J/m^2], found {w_critical!r}")
    w = dissipation_density(result).values
    if np.isnan(w).any():
        raise ValueError("w is unknown for some cycles: they were not recorded whole and the result has no tally")
    accumulated = np.cumsum(w, axis=0)
    reached = accumulated >= w_critical
    if reached.any():
        first = np.argmax(reached, axis=0)  # per node, index of the first cycle that reaches it
        before = np.where(first > 0, accumulated[np.maximum(first - 1, 0), np.arange(w.shape[1])], 0.0)
        gain = w[first, np.arange(w.shape[1])]
        with np.errstate(divide="ignore", invalid="ignore"):
            count = np.where(reached.any(axis=0), first + (w_critical - before) / gain, np.inf)
        method = "interpolated"
    else:
        if w.shape[0] < 2:
            raise ValueError("one cycle cannot show a periodic state: run at least two to extrapolate")
        change = np.abs(w[-1] - w[-2]).max()
        if change > steady_rtol * w[-1].max():
            raise ValueError(
                f"w_critical = {w_critical!r} J/m^2 is not reached in {w.shape[0]} cycles and the last two differ "
                f"by {change:.3g} J/m^2 (more than {steady_rtol:g} of the peak): run on to a periodic state"
            )
        with np.errstate(divide="ignore"):
            count = np.where(w[-1] > 0, w.shape[0] + (w_critical - accumulated[-1]) / w[-1], np.inf)
        method = "extrapolated"
    node = int(np.argmin(count))
    definition = (
        "N_i: least cycle count at which sum_k w_k(x) reaches w_critical at some x, linear in the cycle count "
        "between cycle ends; beyond the run, each later cycle adds the last (periodic) cycle's w(x) "
        "(energy approach, Fouvry, Duo & Perruchaut 2004)"
    )
    return xr.Dataset(
        {
            "N_i": ((), float(count[node]), _attrs("1", "cycles to crack nucleation", definition)),
            "x_i": ((), float(result.x.values[node]), _attrs("m", "nucleation site", "node where N_i is least")),
        },
        attrs={"method": method, "w_critical": float(w_critical)},
    )


def loop_work(result: xr.Dataset) -> xr.Dataset:
    """Work of the loads around each cycle's hysteresis loops and its mismatch with the dissipation.

    ``W = loop Q d(delta_Q) + loop sigma d(delta_sigma)`` by the trapezoidal rule over the
    recorded steps of the cycle, its starting state included (docs/theory/conventions.md#energy). Over a
    closed cycle of a periodic state the loads do no net work on the elastic fields, so ``W``
    equals `cycle_dissipation` to the trapezoidal error (second order in the load step); in a
    transient cycle (e.g. the first one from the virgin state) the stored elastic energy
    changes and the two differ by that change.

    Not for a result of a varying ``P`` (ValueError): ``delta_Q`` weights the slip by the flat punch
    of the current width, so when ``a`` varies it is not the displacement conjugate to ``Q`` (that
    differs from it by ``Q`` times the compliance of the flat punch, ``(2 / (pi E_star)) ln(2L / a)``
    for a continuous one), and ``W`` would not be the work of the loads.

    Returns
    -------
    xarray.Dataset
        Dims (cycle_number,): ``loop_work`` [J/m], ``loop_mismatch`` = ``loop_work / cycle_dissipation
        - 1`` and ``loop_closed`` (the loads end where they started); NaN for cycles not recorded whole.
    """
    _require_cycles(result)
    _refuse_varying_P(result, "loop_work")
    n = result.sizes["cycle_number"]
    work, closed = np.full(n, np.nan), np.zeros(n, dtype=bool)
    Q, sigma = result.Q.values, result.sigma.values
    delta_Q, delta_sigma = result.delta_Q.values, result.delta_sigma.values
    for k, rows in enumerate(complete_cycles(result)):
        if rows is not None:
            work[k] = np.trapezoid(Q[rows], delta_Q[rows]) + np.trapezoid(sigma[rows], delta_sigma[rows])
            closed[k] = Q[rows][0] == Q[rows][-1] and sigma[rows][0] == sigma[rows][-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        mismatch = work / result.cycle_dissipation.values - 1
    definition = "loop Q d(delta_Q) + loop sigma d(delta_sigma) over the cycle, trapezoidal rule on the recorded steps"
    data = {
        "loop_work": ("cycle_number", work, _attrs("J/m", "work of the loads around the cycle", definition)),
        "loop_mismatch": (
            "cycle_number",
            mismatch,
            _attrs("1", "relative mismatch of loop work and dissipation", "loop_work / cycle_dissipation - 1"),
        ),
        "loop_closed": (
            "cycle_number",
            closed,
            _attrs("1", "loads end where they started", "Q and sigma equal at the cycle's first and last state"),
        ),
    }
    return xr.Dataset(data, coords={"cycle_number": result.cycle_number})


def per_cycle(result: xr.Dataset, body: int | None = None, bulk: ArrayLike | None = None) -> xr.Dataset:
    """Every per-cycle scalar of this module in one Dataset, dims (cycle_number,).

    ``E_d``, ``E_d_accumulated``, ``w_max``, ``x_w_max``, ``w_accumulated_max``,
    ``x_w_accumulated_max``, ``slip_amplitude_max`` (the largest slip amplitude, at the node
    ``x_slip_amplitude_max``), ``F1``, ``F2`` with their positions (`ruiz`), and the peak surface
    direct stress ``sigma_xx_max`` over every step of the cycle and the nodes, at the node
    ``x_sigma_xx_max`` (`surface_stress` of `body`, by default the specimen with its bulk stress;
    over every step from the engine's tally ``sigma_xx_peak`` for the specimen with its bulk
    stress, else over the recorded steps of the cycles recorded whole, as `ruiz`).
    """
    body, role = body_role(result, body)
    ruiz_ = ruiz(result, body, bulk)
    delta = _peak(
        slip_amplitude(result),
        "slip_amplitude_max",
        "m",
        "largest slip amplitude of the cycle",
        "max over x of the slip amplitude delta_k(x)",
    )
    stress = xr.DataArray(
        _cycle_peaks(result, body, bulk)["sigma_xx_peak"],
        coords={"cycle_number": result.cycle_number, "x": result.x},
    )
    definition = f"max over every step of the cycle and over x of sigma_xx of the {role} (body {body})"
    peak_stress = _peak(stress, "sigma_xx_max", "Pa", "peak surface direct stress of the cycle", definition)
    parts = [fouvry(result), peak_dissipation_density(result), delta, ruiz_, peak_stress]
    return xr.merge(parts, combine_attrs="drop_conflicts").assign_attrs(body=body, role=role)


def elliptical_traction(
    result: xr.Dataset, rows: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """The traction at `rows` (default: all) of a result on a Hertz contact as an exact model's elliptical loads.

    The exact models on Hertz (`fretting.models.exact`, `fretting.models.inphase`) give ``q`` as a sum
    of loads ``peak sqrt(1 - ((t - e) / c)^2)``. The open turning points at each step follow from
    Masing's rule along the load path, its vertices and the recorded steps (between two of them
    ``Q`` is monotonic); each branch from ``Q_k`` with factor ``m`` (`masing_origin`) adds
    ``sign(Q - Q_k) m f p0 [sqrt(1 - t^2) - (c/a) sqrt(1 - (t - e)^2 a^2 / c^2)]`` with ``c / a =
    sqrt(1 - |Q - Q_k| / (m f P))`` (eq 8 of the seed for the corrective load ``P - |Q - Q_k| / (m f)``)
    and ``e / a = -k |Q - Q_k| / (4 m f p0)`` for in-phase loads ``sigma = k Q`` (Nowell & Hills
    1987; the result's ``sigma_per_Q``, else 0).

    Returns
    -------
    tuple or None
        Half-widths ``c / a`` and centres ``e / a`` (B,) [-] and peaks (steps, B) [Pa], a sparse array
        (each step has a few of the loads of all its steps); None on
        another profile or where they do not meet the recorded traction to `RECONSTRUCTION_RTOL`
        ``f p0``: a traction no exact model gave (a discretised model's), or a run continued from a
        state whose memory the result does not record.
    """
    attrs = result.attrs
    profile = profile_class(recorded_profile(attrs)[0])
    if profile is None or not profile.ELLIPTICAL:
        return None
    rows = np.arange(result.sizes["step"]) if rows is None else rows
    path = dict(zip(result.vertex_step.values.tolist(), result.vertex_Q.values.tolist(), strict=True))
    path |= dict(zip(result.step.values.tolist(), result.Q.values.tolist(), strict=True))
    if path.get(0) != 0.0:
        return None
    memory, turning, before = {}, (), 0.0
    for step in sorted(path):
        turning, _ = masing_increment(turning, before, path[step])
        memory[step], before = turning, path[step]
    fp0, fP = attrs["f"] * attrs["p0"], attrs["f"] * attrs["P"]
    shift = -float(attrs.get("sigma_per_Q", 0.0)) / (4 * fp0)  # e / a per unit |Q - Q_k| / m
    steps = result.step.values[rows].tolist()
    peaks = [_branch_peaks(memory[step], path[step], fP, shift) for step in steps]
    ellipses = sorted({ellipse for peak in peaks for ellipse in peak} | {(1.0, 0.0)})
    index = {ellipse: k for k, ellipse in enumerate(ellipses)}
    entries = [(row, index[ellipse], fp0 * value) for row, peak in enumerate(peaks) for ellipse, value in peak.items()]
    row, column, value = np.array(entries).T
    loads = sparse.csr_array((value, (row.astype(int), column.astype(int))), shape=(len(steps), len(ellipses)))
    widths, centres = np.array(ellipses).T
    t = (result.x.values - attrs["centre"]) / attrs["a"]
    shapes = np.sqrt(np.clip(1 - ((t - centres[:, None]) / widths[:, None]) ** 2, 0, None))
    if np.abs(loads @ shapes - result.q.values[rows]).max(initial=0.0) > RECONSTRUCTION_RTOL * fp0:
        return None
    return widths, centres, loads


def _branch_peaks(turning: tuple, Q: float, fP: float, shift: float) -> dict[tuple[float, float], float]:
    """Peaks per unit ``f p0`` of the elliptical loads of the branches of the open `turning` points at `Q`
    [N/m]: ``{(c / a, e / a): peak}``, ``e / a = shift |Q - Q_k| / m`` (`elliptical_traction`)."""
    peaks = {}
    loads = [*turning, Q]
    for k, load in enumerate(loads):
        origin, factor = masing_origin(turning[:k])
        change = load - origin
        c = float(np.sqrt(max(1 - abs(change) / (factor * fP), 0.0)))
        signed = float(np.sign(change)) * factor
        peaks[1.0, 0.0] = peaks.get((1.0, 0.0), 0.0) + signed
        if c > 0:
            centre = shift * abs(change) / factor
            peaks[c, centre] = peaks.get((c, centre), 0.0) - signed * c
    return peaks
