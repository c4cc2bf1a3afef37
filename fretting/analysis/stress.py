"""Stress fields under the surface of either body, from a result's pressure and shear traction.

Each body is a half-plane in plane strain whose surface carries the contact pressure ``p`` and
the shear traction ``t_x``: ``q`` on body 1 and ``-q`` on body 2 (docs/theory/conventions.md).
Its stress at a point ``(x, z)``, ``z >= 0`` the depth into the body, is the superposition of
Flamant's line-load solutions (Johnson 1985 [1]_, eq 2.23), with ``u = x - s``,
``r^2 = u^2 + z^2``:

    sigma_xx = -(2/pi) int [p(s) z u^2 + t_x(s) u^3] / r^4 ds + sigma_b
    sigma_zz = -(2/pi) int [p(s) z^3 + t_x(s) z^2 u] / r^4 ds
    tau_xz   = -(2/pi) int [p(s) z^2 u + t_x(s) z u^2] / r^4 ds

plus the body's bulk direct stress ``sigma_b`` (`fretting.physics.surface.bulk_stress`). The
contact's field is in plane strain, ``nu (sigma_xx + sigma_zz)`` out of the plane; the bulk
stress is in the state `BULK_STATES` names: held across the width in plane strain (``nu
sigma_b`` out of the plane, the default), or free across it as in a bar in tension (plane
stress, nothing out of the plane). On a strain-based criterion the two differ by up to
``1 / (1 - nu^2)``, 1.099 for ``nu = 0.3``, where the bulk stress dominates (a bulk stress
alone strains along ``x`` by ``(1 - nu^2) sigma_b / E`` in plane strain, by ``sigma_b / E`` in
plane stress). The components are those of the stress
tensor in each body's own frame: ``x`` along the surface as in the result (the axis of
`fretting.analysis.nucleation.surface_stress`), ``z`` into the body. At the surface
``sigma_zz = -p`` and ``tau_xz = -t_x``: ``-q`` in body 1, ``+q`` in body 2; in the frame of
body 1 (``z`` into body 1) body 2's shear stress is ``-tau_xz``.

The integrals are taken in closed form, so the field is exact for the traction each
representation gives:

- elliptical (Hertz-shaped) distributions ``p0 sqrt(1 - (x - e)^2 / c^2)`` by McEwen's closed
  forms [2]_ (`mcewen`): the pressure of a profile that says it is Hertz's
  (`fretting.physics.profiles.Profile.ELLIPTICAL`), and on it a traction that is an exact
  model's, a sum of such distributions (Ciavarella-Jaeger or Nowell-Hills with Masing's rule,
  `fretting.models.exact`, `fretting.models.inphase`) rebuilt from the load path and held against
  the recorded traction (`fretting.analysis.nucleation.elliptical_traction`), so that its field is
  exact to rounding;
- otherwise pressure and traction interpolated linearly between the nodes and zero at the
  contact edges (`polygon`): integrated twice by parts, a continuous piecewise-linear load
  ``g`` gives ``int g(s) K(x - s) ds = sum_k (g'_k+ - g'_k-) F(x - s_k)`` over its knots
  ``s_k``, with ``F'' = K``; the field is that of this interpolant.

The profile is known from the facts the result records, its class ``profile_class``
(`fretting.physics.profiles.recorded_profile`, which reads the ``profile`` repr of a result
written before them); a class this session does not define is taken as one whose pressure
vanishes at the edges, and is integrated piecewise linearly.

References
----------
.. [1] Johnson, Contact Mechanics, Cambridge University Press 1985, eqs 2.22-2.23 (point loads
   on a half-plane) and 7.5, 7.8 (McEwen's fields).
.. [2] McEwen, Stresses in elastic cylinders in contact along a generatrix, Phil. Mag. 40
   (1949) 454-459.
.. [3] Hills & Nowell, Mechanics of Fretting Fatigue, Kluwer 1994, chapter 2 (the partial-slip
   fields as superpositions of McEwen's).
"""

import tomllib

import numpy as np
import xarray as xr
from scipy import special

from fretting._validate import finite_array
from fretting.analysis.nucleation import body_bulk, body_role, elliptical_traction
from fretting.physics.contact import poisson_ratio
from fretting.physics.profiles import profile_class, recorded_profile

__all__ = ["BULK_STATES", "COMPONENTS", "field", "mcewen", "polygon", "with_edges"]

#: name -> (units, long name, definition) of the variables of `field`.
COMPONENTS = {
    "sigma_xx": ("Pa", "direct stress along the surface", "Flamant superposition (Johnson 1985 eq 2.23) + bulk stress"),
    "sigma_zz": ("Pa", "direct stress normal to the surface", "Flamant superposition (Johnson 1985 eq 2.23)"),
    "tau_xz": (
        "Pa",
        "shear stress",
        "Flamant superposition (Johnson 1985 eq 2.23), in the body's frame: x along the surface, z into the "
        "body; -t_x at the surface",
    ),
    "sigma_yy": ("Pa", "direct stress out of the plane", "by the state of the bulk stress (BULK_STATES)"),
}

#: State of the body's bulk stress ``sigma_b`` -> the definition of ``sigma_yy`` it gives (the contact's field is
#: in plane strain either way): held across the width (plane strain), or free across it, as a bar in tension
#: (plane stress).
BULK_STATES = {
    "plane strain": "nu (sigma_xx + sigma_zz): plane strain, the bulk stress included",
    "plane stress": "nu (sigma_xx - sigma_b + sigma_zz): the contact's field in plane strain, the bulk stress "
    "sigma_b in plane stress (uniaxial)",
}

#: Nodes closer than this to an edge, in ``|t| = |x - centre| / a``, are taken as the edge itself (a Galerkin
#: mesh has a node at each edge, ``cos(0)`` and ``cos(pi)`` up to rounding).
EDGE = 1e-12

#: Points evaluated at once: bounds the influence matrices to ~10 MB per component at 400 nodes.
CHUNK = 4096


def mcewen(x, z, half_width, centre=0.0):
    """Field of elliptical pressure and shear, per unit peak, at points ``(x, z)`` [any length unit].

    The loads ``sqrt(1 - (s - centre)^2 / half_width^2)`` on the surface of a half-plane
    (McEwen 1949 [2]_; Johnson 1985 [1]_, eqs 7.5 and 7.8, in the axes of this module), with
    ``m^2, n^2 = (sqrt(A^2 + 4 X^2 z^2) +- A) / 2``, ``A = c^2 - X^2 + z^2``, ``X = x - centre``,
    ``c`` the half-width, ``m >= 0`` and ``n`` of the sign of ``X``:

        pressure: sigma_xx = -(m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2z) / c
                  sigma_zz = -m (1 - (z^2 + n^2)/(m^2 + n^2)) / c
                  tau_xz   = -n (m^2 - z^2)/(m^2 + n^2) / c
        shear:    sigma_xx = (n (2 + (m^2 - z^2)/(m^2 + n^2)) - 2X) / c
                  sigma_zz = pressure's tau_xz,  tau_xz = pressure's sigma_xx

    Each of ``m^2``, ``n^2`` is computed without cancellation (``S - |A| = 4 X^2 z^2 / (S + |A|)``).

    Parameters
    ----------
    x, z : ndarray
        Positions along the surface and depths (``z >= 0``), broadcast together.
    half_width, centre : float
        ``c`` and ``e`` of the distribution, in the unit of `x`.

    Returns
    -------
    ndarray, shape (2, 3, *shape)
        ``[pressure, shear]`` x ``[sigma_xx, sigma_zz, tau_xz]`` per unit peak load.
    """
    X, z = np.broadcast_arrays(np.asarray(x, dtype=float) - centre, np.asarray(z, dtype=float))
    A = half_width**2 - X**2 + z**2
    S = np.hypot(A, 2 * X * z)
    with np.errstate(divide="ignore", invalid="ignore"):
        small = np.where(S + np.abs(A) > 0, 4 * X**2 * z**2 / (S + np.abs(A)), 0.0) / 2
        m2 = np.where(A >= 0, (S + A) / 2, small)
        n2 = np.where(A >= 0, small, (S - A) / 2)
        d = m2 + n2
        ratio = np.where(d > 0, (z**2 + n2) / d, 0.0)  # bounded where d -> 0 (the edges at the surface)
        other = np.where(d > 0, (m2 - z**2) / d, 0.0)
    m, n = np.sqrt(m2), np.copysign(np.sqrt(n2), X)
    sxx_p = -(m * (1 + ratio) - 2 * z)
    txz_p = -n * other
    pressure = [sxx_p, -m * (1 - ratio), txz_p]
    shear = [n * (2 + other) - 2 * X, txz_p, sxx_p]
    return np.array([pressure, shear]) / half_width


def polygon(x, z, knots):
    """Influence of the knot values of a piecewise-linear load on the field at points ``(x, z)``.

    The load is linear between the `knots` and zero at the first and last knot and beyond. With
    ``F'' = K`` for each kernel ``K`` of the module docstring (``u = x - s_k``, ``z > 0``; the
    limit at ``z = 0``), up to a linear function of ``u``, which the sum over knots annihilates:

        K = z u^2 / r^4:  F = u atan(u/z) / 2 - z ln(r^2) / 2
        K = z^3 / r^4:    F = u atan(u/z) / 2
        K = z^2 u / r^4:  F = -z atan(u/z) / 2
        K = u^3 / r^4:    F = u ln(r^2) / 2 + 3 z atan(u/z) / 2

    Parameters
    ----------
    x, z : ndarray, shape (M,)
        Points, depth ``z >= 0``, in the unit of `knots`.
    knots : ndarray, shape (K,)
        Ascending knots, K >= 3.

    Returns
    -------
    ndarray, shape (2, 3, M, K - 2)
        ``[pressure, shear]`` x ``[sigma_xx, sigma_zz, tau_xz]`` per unit value at each
        interior knot.
    """
    u, z = x[:, None] - knots, np.broadcast_to(z[:, None], (x.size, knots.size))
    angle = np.arctan2(u, z)
    F = {
        "a": (u * angle - special.xlogy(z, u**2 + z**2)) / 2,
        "b": u * angle / 2,
        "c": -z * angle / 2,
        "d": special.xlogy(u, u**2 + z**2) / 2 + 1.5 * z * angle,
    }
    width = np.diff(knots)
    weights = {}
    for name, values in F.items():  # sum_k (g'_k+ - g'_k-) F_k = sum_j g_j (G_(j-1) - G_j), G_k = (F_k - F_(k+1)) / h_k
        G = (values[:, :-1] - values[:, 1:]) / width
        weights[name] = G[:, :-1] - G[:, 1:]
    a, b, c, d = (-(2 / np.pi) * weights[name] for name in "abcd")
    return np.array([[a, b, c], [d, c, a]])


def field(result, x, z, step=None, body=None, nu=None, bulk_state="plane strain", edges=True):
    """Stress [Pa] at the points ``(x, z)`` of one body, at recorded steps of a result.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation`.
    x : array_like, shape (X,)
        Positions along the surface [m], on the axis of the result's ``x``.
    z : array_like, shape (Z,)
        Depths into the body [m], ``>= 0``.
    step : int or sequence of int, optional
        Recorded steps to evaluate (default: all of them).
    body : {1, 2} or None
        1: the body whose traction is ``q``; 2: the one with ``-q``; None: the specimen
        (`fretting.analysis.nucleation.specimen`). The specimen carries the bulk stress, the pad
        none (`fretting.physics.surface.bulk_stress`).
    nu : float, optional
        Poisson's ratio, for ``sigma_yy``; by default the ``nu`` the result records (its
        attribute, or for a result written before it, the ``[contact]`` of its ``history_toml``),
        which a result run from ``E_star`` alone does not have.
    bulk_state : {"plane strain", "plane stress"}
        The state of the body's bulk stress ``sigma_b`` (`BULK_STATES`, module docstring): it adds ``nu
        sigma_b`` to ``sigma_yy`` in plane strain, nothing in plane stress (a specimen free across its width).
        The pad carries no bulk stress, so its field is the same in both.
    edges : bool
        Add the contact's edges ``centre +- a`` to an ascending `x` that spans them (`with_edges`). The surface
        stress has a kink at each edge, with an unbounded slope outside it, and a fatigue parameter there its
        largest surface value (the hot spot) in most cycles: without the edges on the grid the hot spot read from
        the map depends on how near a grid point falls to them. False: `x` as given.

    Returns
    -------
    xarray.Dataset
        ``sigma_xx``, ``sigma_zz``, ``tau_xz``, ``sigma_yy`` [Pa] on dims (step, z, x), ``x`` the given
        points and, with `edges`, the contact's edges (`COMPONENTS`; sign conventions in the module
        docstring; ``sigma_yy``'s ``definition`` by `bulk_state`). Attributes: ``body``, ``role``
        (specimen or pad), ``nu``, ``bulk_state``, the contact's ``a``, ``centre``, ``p0``, ``f``, and
        ``traction``, how the loads were integrated: ``"elliptical"`` (McEwen's closed forms:
        the exact model's traction on a Hertz contact) or ``"piecewise linear"``, and
        ``pressure`` likewise (``"elliptical"`` on a Hertz contact).

    Examples
    --------
    The Hertz pressure alone (step 0) has its largest shear stress, ``0.30 p0``, at the depth
    ``0.786 a`` under the centre (Johnson 1985, section 4.2):

    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> result = fr.simulate(contact, fr.History.piecewise_linear([0, 30e3], None, 4), nodes=32)
    >>> point = field(result, [0.0], [0.786 * contact.a], step=0, nu=0.3).isel(step=0, z=0, x=0)
    >>> round(float(point.sigma_xx - point.sigma_zz) / 2 / contact.p0, 3)
    0.3

    Raises
    ------
    ValueError
        On negative or non-finite depths, steps the result does not record, an unknown `body`,
        a missing or invalid `nu`, an unknown `bulk_state`, or a contact whose pressure is unbounded
        at its edges (the flat punch: `fretting.physics.profiles.Profile.VANISHING_EDGES`).
    """
    x, z = finite_array("x", x), finite_array("z", z)
    if bulk_state not in BULK_STATES:
        raise ValueError(f"bulk_state: found {bulk_state!r}, expected one of: {', '.join(map(repr, BULK_STATES))}")
    if np.any(z < 0):
        raise ValueError(f"z must be depths >= 0 into the body [m], found {z.min()!r}")
    body, role = body_role(result, body)
    nu = _poisson(result, nu)
    attrs = result.attrs
    if edges:
        x = with_edges(x, attrs["centre"], attrs["a"])
    profile = profile_class(recorded_profile(attrs)[0])
    if profile is not None and not profile.VANISHING_EDGES:
        raise ValueError(
            f"the pressure of a {profile.__name__} is unbounded at the contact edges: its field is not integrated"
        )
    elliptical = profile is not None and profile.ELLIPTICAL
    rows = _rows(result, step)
    a, centre = attrs["a"], attrs["centre"]
    t, depth = np.meshgrid((x - centre) / a, z / a)  # normalised: every kernel is homogeneous of degree -1
    t, depth = t.ravel(), depth.ravel()
    pressure, pressure_kind = _pressure(result, elliptical)
    traction, loads, traction_kind = _traction(result, rows, elliptical)
    sign = 1.0 if body == 1 else -1.0
    stress = np.empty((3, rows.size, t.size))
    knots, inside = _knots(result)
    linear = pressure_kind == "piecewise linear" or traction_kind == "piecewise linear"
    for chunk in range(0, t.size, CHUNK):
        at = slice(chunk, chunk + CHUNK)
        influence = polygon(t[at], depth[at], knots) if linear else None  # shared by both loads
        p_field = pressure(t[at], depth[at], influence)  # (3, points)
        unit = traction(t[at], depth[at], influence)  # (3, points, basis)
        stress[:, :, at] = p_field[:, None, :] + sign * (unit @ loads.T).transpose(0, 2, 1)
    bulk = body_bulk(result, body)[rows, None, None]
    stress = stress.reshape(3, rows.size, z.size, x.size)
    values = dict(zip(("sigma_xx", "sigma_zz", "tau_xz"), stress, strict=True))
    contact_xx = values["sigma_xx"]
    values["sigma_xx"] = contact_xx + bulk
    in_plane_xx = values["sigma_xx"] if bulk_state == "plane strain" else contact_xx
    values["sigma_yy"] = nu * (in_plane_xx + values["sigma_zz"])
    coords = {"step": result.step.values[rows], "z": z, "x": x}
    definitions = {name: definition for name, (_, _, definition) in COMPONENTS.items()}
    definitions["sigma_yy"] = BULK_STATES[bulk_state]
    data = {
        name: (
            ("step", "z", "x"),
            values[name],
            {"units": units, "long_name": long_name, "definition": definitions[name]},
        )
        for name, (units, long_name, _) in COMPONENTS.items()
    }
    dataset = xr.Dataset(data, coords=coords)
    dataset.z.attrs.update(units="m", long_name="depth into the body")
    dataset.x.attrs.update(units="m", long_name="position along the contact")
    kinds = {"pressure": pressure_kind, "traction": traction_kind}
    return dataset.assign_attrs(
        body=body, role=role, nu=nu, bulk_state=bulk_state, a=a, centre=centre, p0=attrs["p0"], f=attrs["f"], **kinds
    )


def with_edges(x, centre, a):
    """The points `x` [m] with the contact's edges ``centre - a`` and ``centre + a`` among them.

    An edge within the span of an ascending `x` is inserted in order; a point closer to it than `EDGE` ``a`` is
    moved onto it rather than doubled. Any other `x` (not ascending, or not spanning an edge) is returned as given.
    """
    x = np.array(x, dtype=float)
    if x.size < 2 or np.any(np.diff(x) <= 0):
        return x
    for edge in (centre - a, centre + a):
        if x[0] <= edge <= x[-1]:
            near = np.abs(x - edge) <= EDGE * a
            x = np.where(near, edge, x) if near.any() else np.insert(x, np.searchsorted(x, edge), edge)
    return x


def _poisson(result, nu):
    """`nu`, or the one the result records; checked, and the two equal when both are known."""
    recorded = _recorded_poisson(result)
    if nu is None and recorded is None:
        raise ValueError(
            "nu is needed for sigma_yy = nu (sigma_xx + sigma_zz): the result records no Poisson's ratio, pass nu"
        )
    nu = poisson_ratio(recorded if nu is None else nu)
    if recorded is not None and nu != recorded:
        raise ValueError(f"nu = {nu!r} differs from the nu = {recorded!r} the result records")
    return nu


def _recorded_poisson(result):
    """The result's ``nu``: its attribute, else (a result written before it) the ``nu`` of the
    ``[contact]`` table of the history file it records; None when neither is there."""
    if "nu" in result.attrs:
        return float(result.attrs["nu"])
    text = result.attrs.get("history_toml")
    try:
        return None if text is None else tomllib.loads(text).get("contact", {}).get("nu")
    except tomllib.TOMLDecodeError:
        return None


def _rows(result, step):
    """Rows of the recorded `step` numbers (all rows when None)."""
    recorded = result.step.values
    if step is None:
        return np.arange(recorded.size)
    steps = np.atleast_1d(np.asarray(step))
    if steps.ndim != 1 or not np.issubdtype(steps.dtype, np.integer):
        raise ValueError(f"step must be a step number or a list of them, found {step!r}")
    missing = np.setdiff1d(steps, recorded)
    if missing.size:
        raise ValueError(
            f"step {int(missing[0])} is not recorded in the result ({recorded.size} steps recorded, "
            f"from {recorded[0]} to {recorded[-1]})"
        )
    return np.searchsorted(recorded, steps)


def _pressure(result, elliptical):
    """Field of the pressure, ``(t, depth, influence) -> (3, points)`` [Pa] in normalised coordinates
    (`influence`: `polygon` at the knots of `_knots`), and its kind; `elliptical`: Hertz's pressure."""
    if elliptical:
        p0 = result.attrs["p0"]
        return (lambda t, depth, influence: p0 * mcewen(t, depth, 1.0)[0]), "elliptical"
    p = result.p.values[_knots(result)[1]]
    return (lambda t, depth, influence: influence[0] @ p), "piecewise linear"


def _knots(result):
    """Knots ``t`` of the piecewise-linear loads: the nodes inside the contact and its edges, and
    which nodes those are (a node at an edge, where bounded loads vanish, is the edge)."""
    t = (result.x.values - result.attrs["centre"]) / result.attrs["a"]
    inside = np.abs(t) < 1 - EDGE
    return np.concatenate([[-1.0], t[inside], [1.0]]), inside


def _traction(result, rows, elliptical):
    """Field of the shear traction on body 1 per unit basis load, ``(t, depth, influence) -> (3, points, B)``
    (as `_pressure`), the loads (steps, B) [Pa] and its kind; `elliptical`: under Hertz's pressure."""
    ellipses = elliptical_traction(result, rows) if elliptical else None
    if ellipses is not None:
        widths, centres, loads = ellipses
        loads = loads.toarray()
        unit = lambda t, depth, influence: np.stack(  # noqa: E731
            [mcewen(t, depth, c, e)[1] for c, e in zip(widths, centres, strict=True)], axis=-1
        )
        return unit, loads, "elliptical"
    inside = _knots(result)[1]
    return (lambda t, depth, influence: influence[1]), result.q.values[rows][:, inside], "piecewise linear"
