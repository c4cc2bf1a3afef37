"""Direct stress along the surface of a half-plane that carries the contact's tractions.

One formula for the engine, which tallies the specimen's peak stress over every step of a load
cycle, and for `fretting.analysis.nucleation`, which evaluates it at the recorded steps.

Conventions (docs/theory/conventions.md): the shear traction ``q`` acts on body 1 (its resultant is ``Q``)
and ``-q`` on body 2, and ``sigma = sigma_b2 - sigma_b1`` is the difference of the bodies' bulk
direct stresses; by default the specimen (`fretting.physics.contact.SPECIMEN`, or the body a
`Contact` names) carries the bulk stress and the pad none.

References
----------
.. [1] Johnson, Contact Mechanics, Cambridge University Press 1985, section 2.3 (surface
   stresses of a half-plane under distributed tractions).
.. [2] McEwen, Stresses in elastic cylinders in contact along a generatrix, Phil. Mag. 40
   (1949) 454-459.
"""

import numpy as np

from fretting._compiled import njit
from fretting.physics.contact import SPECIMEN

__all__ = [
    "ClosedFormSurfaceStress",
    "SurfaceStress",
    "bulk_stress",
    "ellipse_stress",
    "end_fit",
    "fitted_nodes",
    "gradients",
    "hilbert_matrix",
    "kink_fits",
    "kinks",
    "stick_end_stress",
]

#: Nodes on either side of a stick end whose stress `SurfaceStress.at_stick_ends` takes from the slip's gradient.
END_NODES = 4
#: Nodes on either side of a stick end that the fit of the slip spans (`fitted_nodes`).
FIT_NODES = 6
#: Positions of the stick end that `gradients` fits the slip with at once, over one and a half of the nodes'
#: spacings (two at a kink); the vertex of the parabola through the least residual and its neighbours is the end.
END_CANDIDATES = 48
#: A kink of the slip inside a stick zone (`kinks`) is fitted where the nodal tractions would miss its stress by
#: more than about this fraction of ``f p0``: ``modulus h^2 |d3s/dt3|`` over four stuck nodes above ``KINK f p0``.
KINK = 1e-3
#: A lesser peak of ``h^2 |d3s/dt3|`` within `FIT_NODES` of a kink's, under this fraction of it, is the kink's own
#: (on an uneven mesh); one above it is another kink's, and the two are left to the nodal tractions (`kinks`).
LOBE = 0.5
#: A kink's fit is kept where it leaves less than this fraction of the slip's residual by ``1, u, u^2`` alone:
#: more is left by two kinks the fit takes for one, or by a slip with none, such as one interpolated onto a
#: refined mesh (`SurfaceStress.stick_ends`).
KINK_RESIDUAL = 3e-3


def bulk_stress(sigma, body, bulk=None, specimen=SPECIMEN):
    """Bulk direct stress [Pa] of `body` (1 or 2) from the differential tension `sigma` [Pa].

    `bulk` is body 1's [Pa] and body 2's is ``bulk + sigma``, since only ``sigma = sigma_b2 -
    sigma_b1`` enters the contact. `bulk` None: the `specimen` carries the bulk stress and the pad
    none, so body 1 carries ``-sigma`` when it is the specimen, else nothing. Arrays broadcast.
    """
    if bulk is None:
        bulk = -sigma if specimen == 1 else 0.0
    return bulk if body == 1 else bulk + sigma


class SurfaceStress:
    """``sigma_xx`` [Pa] along the surface of either body at the nodes `t`, the Hilbert matrix precomputed.

    ``sigma_xx(x) = -(2/pi) PV int t_x(xi) / (x - xi) dxi - p(x) + sigma_b`` for a half-plane whose
    surface carries the shear traction ``t_x`` and the pressure ``p`` (Johnson 1985 [1]_, section
    2.3; plane strain), with ``t_x = q`` on body 1 and ``-q`` on body 2, and ``sigma_b`` the body's
    bulk stress. Check: a sliding Hertz contact, ``q = f p``, gives ``-p - 2 f p0 x / a`` in body 1,
    a tension ``2 f p0`` at the trailing edge ``x = -a`` (McEwen 1949 [2]_).

    The principal value is integrated exactly for ``sqrt(1 - t^2) q`` interpolated linearly
    between the nodes (`hilbert_matrix`): one product with an ``N x N`` matrix per step.

    Parameters
    ----------
    t : ndarray, shape (N,)
        Nodes ``(x - centre) / a`` [-], ascending, in [-1, 1].
    """

    def __init__(self, t):
        self._t = np.asarray(t)
        self._root = np.sqrt(1 - np.asarray(t) ** 2)
        self._kernel = 2 * hilbert_matrix(np.asarray(t)).T  # (g @ kernel)_j = (2/pi) PV int ... at t_j

    def __call__(self, q, p, bulk, body):
        """``sigma_xx`` [Pa] of `body` (1 or 2) at the nodes.

        Parameters
        ----------
        q : ndarray, shape (N,) or (steps, N)
            Shear traction on body 1 [Pa].
        p : ndarray, shape (N,)
            Contact pressure [Pa].
        bulk : float or ndarray
            The body's bulk direct stress [Pa] (`bulk_stress`), one value or one per row of `q`
            (shape (steps, 1)).
        body : {1, 2}
        """
        sign = 1.0 if body == 1 else -1.0
        return sign * self.of_traction(q) - p + bulk

    def of_traction(self, q):
        """``-(2/pi) PV int q(xi) / (x - xi) dxi`` [Pa] at the nodes, of `q` [Pa] there (shape (N,) or (steps, N))."""
        return (q * self._root) @ self._kernel

    def at_stick_ends(self, q, p, slip, stuck, sigma, modulus, fp0):
        """This stress of one step with the square-root profile at its stick ends, as `ClosedFormSurfaceStress`.

        A traction ``q = q_st + q_d`` of method 4 (eqs 9, 20 and A.4) gives ``-(2/pi) PV int q / (x - xi) dxi
        = sigma / 2 - E_star ds/dx`` (docs/theory/method4.md#chebyshev: the Hilbert transform of ``sqrt(1 -
        t^2) q_d = -(E_star / 2) sum n c_n T_n`` is ``-(E_star / 2) ds/dx``, and that of ``q_st`` is ``sigma /
        4``): the surface strain mismatch of the two bodies is the slip's gradient. Next to a stick end the
        traction's slope is unbounded and its nodal values miss it, while the slip there goes as ``|x -
        c|^(3/2)`` into the slip zone, which `gradients` fits (`end_fit`). The same holds at a stick end that an
        earlier load left inside today's stick zone (the end ``c*`` at a turning point, Mindlin and
        Deresiewicz): the slip locked in there keeps its ``|x - c*|^(3/2)``, and the stress its square root
        (`kinks` finds those ends, `kink_fits`). The nodes within `END_NODES` of each end take
        ``sigma / 2 - modulus ds/dt``, the others `of_traction` of `q`.

        Parameters
        ----------
        q, p, slip : ndarray, shape (N,)
            Shear traction on body 1 [Pa], pressure [Pa] and slip [m] at the nodes.
        stuck : ndarray of bool, shape (N,)
            Nodes that did not slip in the increment.
        sigma : float
            Differential bulk tension [Pa].
        modulus : float
            ``E_star / a`` [Pa/m].
        fp0 : float
            ``f p0`` [Pa], the scale of the kinks worth fitting (`KINK`).
        """
        stress = self.away_from_ends(q, p, slip, sigma, modulus)
        nodes, values = self.stick_ends(p, slip, stuck, sigma, modulus, fp0)
        stress[nodes] = values
        return ClosedFormSurfaceStress(stress)

    def away_from_ends(self, q, p, slip, sigma, modulus):
        """``-(2/pi) PV int q(xi) / (x - xi) dxi`` [Pa] at the nodes away from the stick ends, of one step or of
        each row of steps (`q`, `p`, `slip` of shape (N,) or (steps, N), `sigma` one value or one per row
        (steps, 1), `modulus` as for `at_stick_ends`): `of_traction` of `q`."""
        return self.of_traction(q)

    def stick_ends(self, p, slip, stuck, sigma, modulus, fp0):
        """The nodes next to the stick ends of one step, today's and the kinks earlier ones left, and their
        ``sigma / 2 - modulus ds/dt`` [Pa] (`at_stick_ends`), among the nodes `in_contact` under the pressure `p`."""
        lower, upper = self.in_contact(p)
        nodes, values = stick_end_stress(
            self._t[lower:upper], slip[lower:upper], stuck[lower:upper], sigma, modulus, fp0
        )
        return nodes + lower, values

    def in_contact(self, p):
        """The first node and the one past the last whose surface strain is the slip's gradient under the pressure `p`
        [Pa]: every node, the contact's own."""
        return 0, self._t.size


class ClosedFormSurfaceStress(SurfaceStress):
    """`SurfaceStress` of a traction whose part ``-(2/pi) PV int q(xi) / (x - xi) dxi`` is known in closed form.

    The exact models' traction on a Hertz contact is a sum of elliptical loads (`fretting.models.exact`,
    `fretting.models.inphase`), each of whose stress is `ellipse_stress`: summed by the model at each
    step, or by `fretting.analysis.nucleation.surface_stress` from the loads it rebuilds, it is exact at
    every node, the square-root profile at each stick end included, which no interpolation of ``q``
    between the nodes gives.

    Parameters
    ----------
    stress : ndarray, shape (N,) or (steps, N)
        That part of the stress of body 1 [Pa] at the nodes.
    """

    def __init__(self, stress):
        self._stress = stress

    def of_traction(self, q):
        """The stress known in closed form [Pa]; `q`, the same traction at the nodes, is not read."""
        return self._stress

    def at_stick_ends(self, *step):
        """This stress itself: exact at the stick ends already."""
        return self


def stick_end_stress(t, slip, stuck, sigma, modulus, fp0):
    """`SurfaceStress.stick_ends` at the nodes `t`: the nodes next to the stick ends and their ``sigma / 2 - modulus
    ds/dt`` [Pa]."""
    current = np.flatnonzero(stuck[1:] != stuck[:-1]) + 1  # node above each stick end
    found = kinks(t, slip, stuck, current, KINK * fp0 / modulus)
    fits = [fit for end in current if (fit := end_fit(t, stuck, end, current)) is not None]
    today = len(fits)
    fits += [fit for end in found for fit in kink_fits(t, end, np.concatenate([current, found]))]
    fitted = gradients(t, slip, fits)
    kept = {}  # kink -> the fit of least residual, where that is under KINK_RESIDUAL
    for fit, (nodes, gradient, share) in zip(fits[today:], fitted[today:], strict=True):
        if share < min(KINK_RESIDUAL, kept.get(fit[1], (0, 0, np.inf))[2]):
            kept[fit[1]] = nodes, gradient, share
    fitted = fitted[:today] + list(kept.values())
    nodes = np.concatenate([np.zeros(0, dtype=int)] + [nodes for nodes, _, _ in fitted])
    gradient = np.concatenate([np.zeros(0)] + [gradient for _, gradient, _ in fitted])
    first = np.unique(nodes, return_index=True)[1]  # a node next to today's end and a kink: today's end's
    nodes, gradient = nodes[first], gradient[first]
    return nodes, sigma / 2 - modulus * gradient


def kinks(t, slip, stuck, ends, floor):
    """Node indices above the kinks of the slip inside the stick zones: the stick ends earlier loads left.

    Where a slip zone stopped growing (a turning point of the load), the slip locked in behind it goes as
    ``A |t - c*|^(3/2)`` into the zone that slipped (`end_fit`), so that its third derivative is
    unbounded there: ``h^2 |d3s/dt3|``, the divided difference over four consecutive stuck nodes of mean
    spacing ``h``, peaks next to ``c*`` at about ``|A| sqrt(h)``, the size of the nodal tractions' error in
    ``ds/dt`` there, where a smooth slip gives a value of order ``h^2``. A window whose value peaks above
    `floor` [m] marks a kink at the node above its middle interval. It is taken where no peak of more than
    `LOBE` of its own (a lesser one is its own, on an uneven mesh) nor any of today's stick `ends` (node
    indices above them) lies within `FIT_NODES` nodes: the fit of `gradients` spans that many nodes on either
    side with one end among them. Kinks nearer to one another than that, as turning points of nearly equal
    loads leave, are left to the nodal tractions.
    """
    if t.size < 4:
        return np.zeros(0, dtype=int)
    first = np.diff(slip) / np.diff(t)
    second = np.diff(first) / (t[2:] - t[:-2])
    size = 6 * np.abs(np.diff(second)) / (t[3:] - t[:-3]) * ((t[3:] - t[:-3]) / 3) ** 2
    size[~(stuck[:-3] & stuck[1:-2] & stuck[2:-1] & stuck[3:])] = 0.0
    window = np.flatnonzero((size > floor) & (size >= np.r_[0.0, size[:-1]]) & (size >= np.r_[size[1:], 0.0]))
    peak, height = window + 2, size[window]
    near = np.abs(peak[:, None] - peak[None, :]) < FIT_NODES
    rival = near & (height[None, :] >= LOBE * height[:, None]) & ~np.eye(peak.size, dtype=bool)
    alone = np.abs(peak[:, None] - np.asarray(ends)[None, :]) >= FIT_NODES
    return peak[~rival.any(axis=1) & alone.all(axis=1)]


def end_fit(t, stuck, end, ends):
    """The fit of the slip about today's stick end below node `end`: ``(nodes, end, side, low, high)`` for
    `gradients`, or None where fewer than two of its nodes stick or three slip, or six in all (a zone narrower
    than that is left to the nodal traction).

    About a stick end ``c`` the slip is the slip locked in before, smooth, plus ``A w^(3/2) + B w^(5/2)``
    with ``w`` the distance into the slip zone (eq 19; Masing's rule for reversed zones), on the `side` (+1 or
    -1 along ``t``) of the slipping node; the end lies between the stuck node, less half a spacing inward,
    and the slipping node (the model's ends are within that): [`low`, `high`]. The nodes are `fitted_nodes`.
    """
    nodes = fitted_nodes(end, ends, t.size)
    side = 1.0 if stuck[end - 1] else -1.0
    slipping = np.count_nonzero(side * (nodes - end + 0.5) > 0)
    if slipping < 3 or nodes.size - slipping < 2 or nodes.size < 6:
        return None
    inner = end - 1 if side > 0 else end  # the stuck node
    inward = t[min(max(inner - int(side), 0), t.size - 1)] - t[inner]
    low, high = sorted((t[inner] + inward / 2, t[end] if side > 0 else t[end - 1]))
    return nodes, end, side, low, high


def kink_fits(t, end, ends):
    """The two fits of the slip about the kink below node `end` (`kinks`), one for the earlier slip zone on
    either side (`gradients` keeps the one of least residual), the kink between nodes ``end - 2`` and ``end + 1``
    (the window that found it) and with three of its `fitted_nodes` at least on either side; none where that
    leaves no room."""
    nodes = fitted_nodes(end, ends, t.size)
    if nodes.size < 6:
        return []
    low, high = max(t[end - 2], t[nodes[2]]), min(t[end + 1], t[nodes[-3]])
    return [(nodes, end, side, low, high) for side in (1.0, -1.0)] if low < high else []


def fitted_nodes(end, ends, N):
    """The `FIT_NODES` nodes on either side of the end below node `end`, of `N`, that lie nearer to it than to
    the other `ends` (node indices like `end`)."""
    nodes = np.arange(max(end - FIT_NODES, 0), min(end + FIT_NODES, N))
    others = ends[ends != end]
    if others.size:
        nodes = nodes[np.abs(nodes - end + 0.5) < np.abs(nodes[:, None] - others + 0.5).min(axis=1)]
    return nodes


def gradients(t, slip, fits):
    """``ds/dt`` [m] at the nodes next to each end of `fits`, fitting the slip with ``|t - c|^(3/2)``.

    Each fit ``(nodes, end, side, low, high)`` (`end_fit`, `kink_fits`) takes the slip at its `nodes` by least
    squares with ``1, u, u^2, w^(3/2), w^(5/2)``, ``u = (t - c) / h``, ``w = max(side u, 0)``, ``h`` the spacing
    at the end, for `END_CANDIDATES` ends ``c`` in [low, high]; the end is the vertex of the parabola through
    the least residual and its neighbours, and the fit there is differentiated at the `END_NODES` nodes
    nearest the end on either side. All fits of a step are solved at once.

    Returns
    -------
    list
        For each fit, its node indices (K,), ``ds/dt`` [m] there, and its residual over that of ``1, u, u^2``
        alone (1 where that is none).
    """
    if not fits:
        return []
    rows = np.arange(len(fits))
    index, known = np.zeros((rows.size, 2 * FIT_NODES), dtype=int), np.zeros((rows.size, 2 * FIT_NODES), dtype=bool)
    for row, (nodes, *_) in enumerate(fits):
        index[row, : nodes.size], known[row, : nodes.size] = nodes, True
    end, side, low, high = (np.array(column) for column in list(zip(*fits, strict=True))[1:])
    h = t[end] - t[end - 1]
    y = np.where(known, slip[index], 0.0)
    scale = np.abs(y).max(axis=1)
    scale[scale == 0] = 1.0  # [m]
    y = y / scale[:, None]
    c = np.linspace(low, high, END_CANDIDATES, axis=1)
    residual, quadratic = _residuals(t[index] - t[end, None], known, y, c - t[end, None], side, h)
    best = np.clip(np.argmin(residual, axis=1), 1, END_CANDIDATES - 2)
    r0, r1, r2 = residual[rows, best - 1], residual[rows, best], residual[rows, best + 1]
    curvature = r0 - 2 * r1 + r2
    shift = np.where(curvature > 0, np.clip(0.5 * (r0 - r2) / np.where(curvature > 0, curvature, 1.0), -1, 1), 0.0)
    at = c[rows, best] + shift * (c[:, 1] - c[:, 0])
    coefficients, u, w, residual = _fit(t[index], known, y, at[:, None], side, h)
    _, a1, a2, a3, a4 = (coefficients[:, 0, k, None] * scale[:, None] for k in range(5))
    u, w, slope = u[:, 0], w[:, 0], side[:, None]
    gradient = (a1 + 2 * a2 * u + slope * (1.5 * a3 * np.sqrt(w) + 2.5 * a4 * w**1.5)) / h[:, None]
    near = known & (np.abs(index - end[:, None] + 0.5) < END_NODES)
    share = np.divide(residual[:, 0], quadratic, out=np.ones_like(quadratic), where=quadratic > 0)
    return [(index[row, near[row]], gradient[row, near[row]], share[row]) for row in rows]


def _residuals(t, known, y, c, side, h):
    """The residuals (F, C) of `_fit` at each end of `c` (F, C), from the parts of `y` and of the columns ``w^(3/2),
    w^(5/2)`` (``w = max(side (t - c) / h, 0)``) that ``1, t, t^2``, the same at every end, leave; and the
    residual of ``1, t, t^2`` alone (F,) (`_residual_kernel`)."""
    residual, quadratic = np.empty(c.shape), np.empty(c.shape[0])
    _residual_kernel(t / h[:, None], known, y, c / h[:, None], side, residual, quadratic)
    return residual, quadratic


@njit
def _residual_kernel(v, known, y, c, side, residual, quadratic):
    """`_residuals` in ``v = t / h`` and ``c / h``, written to `residual` and `quadratic`: per fit, ``1, v, v^2``
    made orthonormal over its `known` nodes (Gram-Schmidt, twice for rounding), `y` and then the two columns of
    each end less their parts along them, and the two columns' least squares in closed form (`_explained`)."""
    F, n = v.shape
    Q, part, w0, w1 = np.zeros((3, n)), np.zeros(n), np.zeros(n), np.zeros(n)
    for f in range(F):
        for k in range(3):
            for m in range(n):
                Q[k, m] = v[f, m] ** k if known[f, m] else 0.0
            for _ in range(2):
                for j in range(k):
                    Q[k] -= (Q[j] @ Q[k]) * Q[j]
            norm = np.sqrt(Q[k] @ Q[k])
            if norm > 0:
                Q[k] /= norm
        for m in range(n):
            part[m] = y[f, m] if known[f, m] else 0.0
        for k in range(3):
            part -= (Q[k] @ part) * Q[k]
        quadratic[f] = part @ part
        for e in range(c.shape[1]):
            for m in range(n):
                w = max(side[f] * (v[f, m] - c[f, e]), 0.0) if known[f, m] else 0.0
                w0[m] = w * np.sqrt(w)
                w1[m] = w0[m] * w
            for k in range(3):
                w0 -= (Q[k] @ w0) * Q[k]
                w1 -= (Q[k] @ w1) * Q[k]
            explained = _explained(w0 @ w0, w0 @ w1, w1 @ w1, w0 @ part, w1 @ part)
            residual[f, e] = quadratic[f] - explained


@njit
def _explained(g00, g01, g11, b0, b1):
    """``b^T G^+ b`` for the symmetric positive semi-definite 2 x 2 matrix ``G`` and the vector ``b``: the square
    norm of the least-squares fit of a target by two columns of Gram matrix ``G`` and inner products ``b`` with
    the target (by the first alone where they are proportional, as with one node in the slip zone)."""
    det = g00 * g11 - g01 * g01
    if det > 1e-12 * g00 * g11:
        return (g11 * b0 * b0 - 2 * g01 * b0 * b1 + g00 * b1 * b1) / det
    return b0 * b0 / g00 if g00 > 0 else 0.0


def _fit(t, known, y, c, side, h):
    """Least squares of `y` at `t` (F, n), rows `known`, by ``1, u, u^2, w^(3/2), w^(5/2)`` with ``u = (t - c) /
    h``, ``w = max(side u, 0)``, for each end of `c` (F, C) of each of F fits (`side`, `h`: (F,)):
    coefficients (F, C, 5), ``u`` and ``w`` (F, C, n), residuals (F, C)."""
    u = (t[:, None, :] - c[:, :, None]) / h[:, None, None]
    w = np.maximum(side[:, None, None] * u, 0.0)
    basis = np.stack([np.ones_like(u), u, u**2, w**1.5, w**2.5], axis=-1) * known[:, None, :, None]
    transposed = basis.swapaxes(-1, -2)  # normal equations, of columns of order 1 over the fitted nodes
    target = np.broadcast_to(y[:, None, :, None], (*u.shape, 1))
    try:
        coefficients = np.linalg.solve(transposed @ basis, transposed @ target)[..., 0]
    except np.linalg.LinAlgError:  # columns dependent at some end (a slip zone of three nodes): least norm
        coefficients = (np.linalg.pinv(basis) @ target)[..., 0]
    residual = np.sum(((basis @ coefficients[..., None])[..., 0] - y[:, None, :]) ** 2, axis=-1)
    return coefficients, u, w, residual


def ellipse_stress(t, half_width, centre=0.0):
    """``-(2/pi) PV int sqrt(1 - ((s - e) / c)^2) / (t - s) ds`` [-] at `t`: the surface ``sigma_xx`` per unit peak.

    The elliptical shear load of half-width ``c`` centred at ``e`` (all lengths in one unit; arrays
    broadcast) gives ``-2 X / c`` inside (``X = t - e``, ``|X| < c``) and ``-2 (X - sign(X) sqrt(X^2 -
    c^2)) / c`` outside, written ``-2 sign(X) c / (|X| + sqrt(X^2 - c^2))`` without cancellation
    (McEwen 1949 [2]_ at the surface; Johnson 1985 [1]_, eq 7.8 at ``z = 0``). The stress has a
    vertical tangent outside each end of the load, where the traction's slope is unbounded.
    """
    X = np.asarray(t, dtype=float) - centre
    c = np.asarray(half_width, dtype=float)
    outside = np.sqrt(np.clip((np.abs(X) - c) * (np.abs(X) + c), 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        beyond = np.sign(X) * c / (np.abs(X) + outside)
    return -2 * np.where(np.abs(X) < c, X / c, beyond)


def hilbert_matrix(t):
    """Matrix ``H`` with ``(1/pi) PV int_{-1}^{1} g(tau) / (sqrt(1 - tau^2) (tau - t_j)) dtau = (H @ g)_j``.

    ``g`` is interpolated linearly between the nodes `t` (ascending, in [-1, 1]) and extrapolated
    linearly from the two outermost nodes to ``+-1`` where no node lies there; each piece
    ``A + B tau`` is integrated exactly (product integration):
    ``int (A + B tau) dtau / (sqrt(1 - tau^2) (tau - t)) = B int dtau / sqrt(1 - tau^2)
    + (A + B t) int dtau / (sqrt(1 - tau^2) (tau - t))``, and with ``tau = cos(theta)``,
    ``t = cos(phi)``, ``int dtheta / (cos(theta) - cos(phi)) = ln|sin((theta + phi)/2) /
    sin((theta - phi)/2)| / sin(phi)``. Writing ``A + B t = g(t) + (A + B t - g(t))``, the first
    part integrates to ``g(t) U_{-1}(t) = 0`` over (-1, 1) (docs/theory/method4.md#chebyshev) and the second
    vanishes on the two pieces that meet at ``t``, so no principal value is left to take.

    A node at ``t = 1`` or ``-1`` (a Galerkin mesh has both) is its own end knot, and its row is
    the limit there, finite where ``g`` vanishes at that end as ``g = q sqrt(1 - t^2)`` does: the
    piece that meets it drops out and the others integrate to differences of ``cot(theta/2)`` at
    ``t = 1`` and of ``tan(theta/2)`` at ``t = -1`` (``dtau / (sqrt(1 - tau^2) (tau -+ 1))`` in ``theta``).
    """
    N = t.size
    lower, upper = int(t[0] > -1.0), int(t[-1] < 1.0)  # end knots to add
    knots = np.concatenate([[-1.0] * lower, t, [1.0] * upper])
    at = np.arange(N) + lower  # knot of each node
    extend = np.zeros((knots.size, N))  # knot values from node values
    extend[at, np.arange(N)] = 1.0
    for add, end, (inner, outer) in ((lower, 0, (0, 1)), (upper, knots.size - 1, (N - 1, N - 2))):
        if add:
            u = (knots[end] - t[inner]) / (t[outer] - t[inner])
            extend[end, inner], extend[end, outer] = 1 - u, u
    theta = np.arccos(knots)
    cauchy = np.zeros((N, knots.size - 1))  # int over piece k of dtau / (sqrt(1 - tau^2) (tau - t_j))
    inside = np.abs(t) < 1
    phi = np.arccos(t[inside])[:, None]
    with np.errstate(divide="ignore"):
        log = np.log(np.abs(np.sin((theta + phi) / 2) / np.sin((theta - phi) / 2))) / np.sin(phi)
        ends = {1.0: 1 / np.tan(theta / 2), -1.0: np.tan(theta / 2)}
    cauchy[inside] = log[:, :-1] - log[:, 1:]
    for j in np.flatnonzero(~inside):
        cauchy[j] = ends[t[j]][:-1] - ends[t[j]][1:]
    pieces = np.stack([at - 1, at], axis=1)  # the two pieces that meet at each node
    valid = (pieces >= 0) & (pieces < knots.size - 1)
    cauchy[np.nonzero(valid)[0], pieces[valid]] = 0.0
    low, high = knots[:-1], knots[1:]
    width = high - low
    arc = (theta[:-1] - theta[1:]) / width  # B_k times this is the arcsine part
    below = (high - t[:, None]) / width * cauchy  # weight of the piece's lower knot in (A + B t_j) cauchy
    above = (t[:, None] - low) / width * cauchy
    H = np.zeros((N, knots.size))
    H[:, :-1] += below - arc
    H[:, 1:] += above + arc
    H[np.flatnonzero(inside), at[inside]] -= cauchy[inside].sum(axis=1)  # the - g(t_j) sum_k cauchy_jk part
    return H @ extend / np.pi
