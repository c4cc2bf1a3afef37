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

from fretting.physics.contact import SPECIMEN

__all__ = [
    "ClosedFormSurfaceStress",
    "SurfaceStress",
    "bulk_stress",
    "ellipse_stress",
    "hilbert_matrix",
    "slip_gradient_at_end",
]

#: Nodes on either side of a stick end whose stress `SurfaceStress.at_stick_ends` takes from the slip's gradient.
END_NODES = 4
#: Nodes on either side of a stick end that the fit of the slip spans (`slip_gradient_at_end`).
FIT_NODES = 6
#: Positions of the stick end that `slip_gradient_at_end` fits the slip with at once, over one and a half of the
#: nodes' spacings; the vertex of the parabola through the least residual and its neighbours is the end.
END_CANDIDATES = 48


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

    def at_stick_ends(self, q, slip, stuck, sigma, modulus):
        """This stress of one step with the square-root profile at its stick ends, as `ClosedFormSurfaceStress`.

        A traction ``q = q_st + q_d`` of method 4 (eqs 9, 20 and A.4) gives ``-(2/pi) PV int q / (x - xi) dxi
        = sigma / 2 - E_star ds/dx`` (docs/theory/method4.md#chebyshev: the Hilbert transform of ``sqrt(1 -
        t^2) q_d = -(E_star / 2) sum n c_n T_n`` is ``-(E_star / 2) ds/dx``, and that of ``q_st`` is ``sigma /
        4``): the surface strain mismatch of the two bodies is the slip's gradient. Next to a stick end the
        traction's slope is unbounded and its nodal values miss it, while the slip there goes as ``|x -
        c|^(3/2)`` into the slip zone, which `slip_gradient_at_end` fits. The nodes within `END_NODES` of each
        stick end (between a node that stuck in the increment and one that slipped) take ``sigma / 2 -
        modulus ds/dt``, the others `of_traction` of `q`.

        Parameters
        ----------
        q, slip : ndarray, shape (N,)
            Shear traction on body 1 [Pa] and slip [m] at the nodes.
        stuck : ndarray of bool, shape (N,)
            Nodes that did not slip in the increment.
        sigma : float
            Differential bulk tension [Pa].
        modulus : float
            ``E_star / a`` [Pa/m].
        """
        stress = self.of_traction(q)
        nodes, values = self.stick_ends(slip, stuck, sigma, modulus)
        stress[nodes] = values
        return ClosedFormSurfaceStress(stress)

    def stick_ends(self, slip, stuck, sigma, modulus):
        """The nodes next to the stick ends of one step and their ``sigma / 2 - modulus ds/dt`` [Pa]
        (`at_stick_ends`)."""
        ends = np.flatnonzero(stuck[1:] != stuck[:-1]) + 1  # node above each stick end
        fitted = [slip_gradient_at_end(self._t, slip, stuck, end, ends) for end in ends]
        nodes = np.concatenate([np.zeros(0, dtype=int)] + [nodes for nodes, _ in fitted])
        gradient = np.concatenate([np.zeros(0)] + [gradient for _, gradient in fitted])
        return nodes, sigma / 2 - modulus * gradient


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


def slip_gradient_at_end(t, slip, stuck, end, ends):
    """``ds/dt`` [m] at the nodes next to the stick end below node `end`, fitting the slip with ``|t - c|^(3/2)``.

    About a stick end ``c`` the slip is the slip locked in before, smooth, plus ``A w^(3/2) + B w^(5/2)``
    with ``w`` the distance into the slip zone (eq 19; Masing's rule for reversed zones). The slip of the
    `FIT_NODES` nodes on either side of the end (those nearer to it than to the other `ends`, node indices
    like `end`) is fitted by least squares with ``1, u, u^2, w^(3/2), w^(5/2)``, ``u = t - c``, with ``c``
    the one of least residual from the stuck node half a spacing inward to the slipping node (the model's
    ends are within that: `END_CANDIDATES`), and differentiated at the `END_NODES` nodes nearest on either side.

    Returns
    -------
    tuple
        Node indices (K,) and ``ds/dt`` [m] there; none where fewer than two nodes stick or three slip, or six
        in all (a zone narrower than that is left to the nodal traction).
    """
    nodes = np.arange(max(end - FIT_NODES, 0), min(end + FIT_NODES, t.size))
    others = ends[ends != end]
    if others.size:
        nodes = nodes[np.abs(nodes - end + 0.5) < np.abs(nodes[:, None] - others + 0.5).min(axis=1)]
    side, h = (1.0 if stuck[end - 1] else -1.0), t[end] - t[end - 1]
    slipping = np.count_nonzero(side * (nodes - end + 0.5) > 0)
    if slipping < 3 or nodes.size - slipping < 2 or nodes.size < 6:
        return np.zeros(0, dtype=int), np.zeros(0)
    inner = end - 1 if side > 0 else end  # the stuck node
    inward = t[min(max(inner - int(side), 0), t.size - 1)] - t[inner]
    scale = np.abs(slip[nodes]).max() or 1.0  # [m]
    y = slip[nodes] / scale
    low, high = sorted((t[inner] + inward / 2, t[end] if side > 0 else t[end - 1]))
    c = np.linspace(low, high, END_CANDIDATES)
    residual = _fit(t[nodes], y, c, side, h)[3]
    best = int(np.clip(np.argmin(residual), 1, END_CANDIDATES - 2))
    r0, r1, r2 = residual[best - 1 : best + 2]
    curvature = r0 - 2 * r1 + r2  # the vertex of the parabola through the least residual and its neighbours
    shift = np.clip(0.5 * (r0 - r2) / curvature, -1.0, 1.0) if curvature > 0 else 0.0
    coefficients, u, w, _ = _fit(t[nodes], y, c[best : best + 1] + shift * (c[1] - c[0]), side, h)
    coefficients, u, w = coefficients[0] * scale, u[0], w[0]
    near = np.abs(nodes - end + 0.5) < END_NODES
    u, w = u[near], w[near]
    gradient = (
        coefficients[1]
        + 2 * coefficients[2] * u
        + side * (1.5 * coefficients[3] * np.sqrt(w) + 2.5 * coefficients[4] * w**1.5)
    )
    return nodes[near], gradient / h


def _fit(t, y, c, side, h):
    """Least squares of `y` at `t` by ``1, u, u^2, w^(3/2), w^(5/2)`` with ``u = (t - c) / h``, ``w = max(side u, 0)``,
    for each end ``c`` of `c` (C,): coefficients (C, 5), ``u`` and ``w`` (C, n), residuals (C,)."""
    u = (t - c[:, None]) / h
    w = np.maximum(side * u, 0.0)
    basis = np.stack([np.ones_like(u), u, u**2, w**1.5, w**2.5], axis=-1)
    transposed = basis.transpose(0, 2, 1)  # normal equations, of columns of order 1 over the fitted nodes
    try:
        coefficients = np.linalg.solve(transposed @ basis, transposed @ y[:, None])[..., 0]
    except np.linalg.LinAlgError:  # columns dependent at some end (a slip zone of three nodes): least norm
        coefficients = (np.linalg.pinv(basis) @ y[:, None])[..., 0]
    residual = np.sum(((basis @ coefficients[..., None])[..., 0] - y) ** 2, axis=1)
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
