"""Load histories: the shear force Q, the bulk tension sigma and, where it varies, the normal load P, at every step."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fretting._validate import finite, finite_array, positive
from fretting.errors import HistoryError

__all__ = ["History", "RAMP_STEPS"]

#: Steps of the straight ramp that reaches the first point of a sinusoid: a quarter of the
#: default 64 steps per cycle, the steps a sinusoid takes to rise from its mean to its peak.
RAMP_STEPS = 16

#: Steps that a pass over a whole history (`History.largest_Q_below`, the check of its cycle
#: numbers) takes at a time: its temporary arrays stay small however long the history.
BLOCK_STEPS = 2**20

#: Largest cycle number of a history: its cycle numbers are held as int32.
CYCLE_LIMIT = np.iinfo(np.int32).max


@dataclass(frozen=True, eq=False)
class History:
    """Loads at every step; step 0 is the starting state.

    Attributes
    ----------
    Q : ndarray, shape (n_steps,)
        Shear force per unit length [N/m].
    sigma : ndarray, shape (n_steps,)
        Differential bulk tension [Pa].
    vertex_step : ndarray of int, shape (n_vertices,)
        Step at which each vertex of the path is reached.
    cycle : ndarray of int32, shape (n_steps,), optional
        Load cycle (1, 2, ...) that the increment ending at each step belongs to; 0 for
        steps outside any cycle (the starting state, ramps). Each cycle is one run of steps:
        the non-zero numbers never decrease. None for histories without cycles. Held in 32 bits
        (at most `CYCLE_LIMIT`): 4 bytes a step of a long history.
    P : ndarray, shape (n_steps,), optional
        Normal load per unit length [N/m], positive; step 0 is the load at which the contact is
        formed (the contact's ``P``). None: the contact's constant ``P``.
    """

    Q: np.ndarray
    sigma: np.ndarray
    vertex_step: np.ndarray
    cycle: np.ndarray | None = None
    P: np.ndarray | None = None

    def __post_init__(self):
        Q = _loads("Q", self.Q)
        sigma = _loads("sigma", self.sigma)
        if Q.shape != sigma.shape:
            raise HistoryError(f"Q and sigma must have the same length, found {Q.size} and {sigma.size}")
        vertex_step = np.asarray(self.vertex_step, dtype=np.int64)
        if vertex_step.ndim != 1 or np.any(np.diff(vertex_step) < 0) or np.any(vertex_step >= Q.size):
            raise HistoryError("vertex_step must be non-decreasing steps of the history")
        arrays = {"Q": Q, "sigma": sigma, "vertex_step": vertex_step}
        if self.cycle is not None:
            cycle = np.asarray(self.cycle)
            if cycle.shape != Q.shape or not np.issubdtype(cycle.dtype, np.integer) or np.any(cycle < 0):
                raise HistoryError("cycle must give a cycle number >= 0 for every step, non-zero ones non-decreasing")
            if cycle.size and cycle.max() > CYCLE_LIMIT:
                raise HistoryError(f"cycle numbers must be at most {CYCLE_LIMIT}, found {cycle.max()}")
            cycle = cycle.astype(np.int32, copy=False)
            if _positives_decrease(cycle):
                raise HistoryError("cycle must give a cycle number >= 0 for every step, non-zero ones non-decreasing")
            arrays["cycle"] = cycle
        if self.P is not None:
            arrays["P"] = _normal_loads(self.P, Q.size)
        for name, value in arrays.items():
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    def __len__(self):
        return self.Q.size

    def __getitem__(self, steps):
        """Contiguous steps ``history[start:stop]``, renumbered from 0, with their vertices and cycles.

        Cycle numbers are kept, so that a run continued from step ``k`` with ``history[k:]``
        numbers its cycles as the whole run does.
        """
        if not isinstance(steps, slice) or steps.step not in (None, 1):
            raise TypeError(f"a History takes contiguous slices of steps, e.g. history[k:], found {steps!r}")
        start, stop, _ = steps.indices(len(self))
        if stop <= start:
            raise HistoryError(f"steps {start}:{stop} of a {len(self)}-step history are empty")
        inside = slice(*np.searchsorted(self.vertex_step, [start, stop]))  # vertex_step is sorted
        cycle = None if self.cycle is None else self.cycle[start:stop]
        P = None if self.P is None else self.P[start:stop]
        return History(self.Q[start:stop], self.sigma[start:stop], self.vertex_step[inside] - start, cycle, P)

    @property
    def normal_start(self):
        """Normal load ``P`` at step 0 [N/m], None where the history does not vary it."""
        return None if self.P is None else float(self.P[0])

    @property
    def start(self):
        """Loads ``(Q, sigma)`` at step 0 [N/m], [Pa]."""
        return float(self.Q[0]), float(self.sigma[0])

    @property
    def end(self):
        """Loads ``(Q, sigma)`` at the last step [N/m], [Pa]."""
        return float(self.Q[-1]), float(self.sigma[-1])

    @property
    def normal_end(self):
        """Normal load ``P`` at the last step [N/m], None where the history does not vary it."""
        return None if self.P is None else float(self.P[-1])

    @property
    def cycle_count(self):
        """Number of the last load cycle; 0 for a history without cycles."""
        return int(_cycles(self).max())

    def largest_Q_below(self, bound):
        """Largest ``|Q|`` [N/m] of the steps where it is below `bound` [N/m]; 0 if there is none.

        Taken `BLOCK_STEPS` steps at a time, with no temporary array of the whole history.
        """
        largest = 0.0
        for Q, _ in self.blocks():
            loads = np.abs(Q)
            largest = max(largest, float(loads.max(where=loads < bound, initial=0.0)))
        return largest

    def blocks(self):
        """``(Q, sigma)`` [N/m], [Pa] of `BLOCK_STEPS` steps at a time, in order (views, not copies).

        A pass over a long history block by block makes temporary arrays of one block, not of
        the whole history.
        """
        for start in range(0, len(self), BLOCK_STEPS):
            yield self.Q[start : start + BLOCK_STEPS], self.sigma[start : start + BLOCK_STEPS]

    def turning_steps(self, max_turn=None, units=(1.0, 1.0)):
        """Steps of the path's turning points, ascending: the first and last steps, the vertices, the
        steps where Q or sigma reverses or stops, and, given `max_turn`, the steps where a curved
        stretch bends.

        Between turning points Q and sigma are monotonic, and along a proportional stretch the
        state reached does not depend on the steps taken (a slip zone only grows while the load
        grows), so the stick and slip zones at these steps are those that the energy of a
        proportional path depends on. A curved (non-proportional) stretch is cut where its
        direction in the plane of ``(Q / units[0], sigma / units[1])`` has turned by another
        `max_turn` [rad] from its first direction, so that each piece is nearly straight; a
        straight stretch is not cut.

        Parameters
        ----------
        max_turn : float, optional
            Turn of the path's direction [rad] between cuts of a curved stretch (None: no cuts).
        units : tuple of float
            Units of Q [N/m] and sigma [Pa] in which the direction is measured.
        """
        kept = np.zeros(len(self), dtype=bool)
        kept[[0, -1]] = True
        kept[self.vertex_step] = True
        for load in (self.Q, self.sigma) if self.P is None else (self.Q, self.sigma, self.P):
            direction = np.diff(load)
            np.sign(direction, out=direction)  # in place: the history may be long
            before, after = direction[:-1], direction[1:]
            kept[1:-1] |= (before != after) & (before != 0)
        if max_turn is not None and np.ptp(self.Q) and np.ptp(self.sigma):  # a path along one axis never bends
            max_turn, units = positive("max_turn", max_turn), [positive("units", unit) for unit in units]
            kept[_bends(self.Q, self.sigma, kept, max_turn, units)] = True
        return np.flatnonzero(kept)

    def turning_points(self, max_turn=None, units=(1.0, 1.0)):
        """The path through its turning points only (`turning_steps`): vertices, cycles and loads
        are kept; steps are renumbered."""
        steps = self.turning_steps(max_turn, units)
        cycle = None if self.cycle is None else self.cycle[steps]
        P = None if self.P is None else self.P[steps]
        return History(self.Q[steps], self.sigma[steps], np.searchsorted(steps, self.vertex_step), cycle, P)

    def as_cycle(self):
        """The same path counted as one load cycle: every step after the first belongs to cycle 1."""
        cycle = np.ones(len(self), dtype=np.int64)
        cycle[0] = 0
        return History(self.Q, self.sigma, self.vertex_step, cycle, self.P)

    @classmethod
    def concatenate(cls, histories):
        """One history after the other.

        Parameters
        ----------
        histories : iterable of History
            Each must start exactly where the previous one ends; its step 0, which repeats
            that point, is dropped.

        Returns
        -------
        History
            Cycles are counted on: those of each history are numbered after the previous ones.
            None if no history has cycles.
        """
        histories = list(histories)
        if not histories:
            raise HistoryError("no histories to concatenate")
        if len(histories) == 1:  # not copied: its arrays may be large, and they cannot change
            return histories[0]
        first = histories[0]
        varies = {history.P is not None for history in histories}
        if len(varies) > 1:
            raise HistoryError("histories with a normal load P and without one cannot be concatenated")
        Q, sigma, vertex_step, cycle = [first.Q], [first.sigma], [first.vertex_step], [_cycles(first)]
        P = [first.P] if first.P is not None else None
        end, last_vertex, counted = len(first) - 1, first.vertex_step.max(initial=-1), first.cycle_count
        for number, (previous, history) in enumerate(itertools.pairwise(histories), start=2):
            if (history.start, history.normal_start) != (previous.end, previous.normal_end):
                raise HistoryError(
                    f"history {number} starts at (Q, sigma) = {history.start}, P = {history.normal_start}, "
                    f"expected the end of the previous one, {previous.end}, P = {previous.normal_end}"
                )
            vertices = history.vertex_step[history.vertex_step > 0] if last_vertex == end else history.vertex_step
            later = _cycles(history)[1:]
            Q.append(history.Q[1:])
            sigma.append(history.sigma[1:])
            if P is not None:
                P.append(history.P[1:])
            vertex_step.append(vertices + end)
            cycle.append(np.where(later > 0, later + counted, 0))
            last_vertex = vertices[-1] + end if vertices.size else last_vertex
            end, counted = end + len(history) - 1, counted + history.cycle_count
        has_cycles = any(history.cycle is not None for history in histories)
        return cls(
            *map(np.concatenate, (Q, sigma, vertex_step)),
            np.concatenate(cycle) if has_cycles else None,
            None if P is None else np.concatenate(P),
        )

    @classmethod
    def piecewise_linear(
        cls,
        Q: ArrayLike,
        sigma: ArrayLike | None = None,
        steps_per_segment: int | ArrayLike = 16,
        P: ArrayLike | None = None,
    ) -> History:
        """Straight segments between vertices of the (Q, sigma) path, or of the (P, Q, sigma) path.

        Parameters
        ----------
        Q : array_like
            Shear force at the vertices [N/m]; the first vertex is the starting state.
        sigma : array_like, optional
            Bulk tension at the vertices [Pa]; zero when omitted.
        steps_per_segment : int or array_like of int
            Equal increments of each segment (one number for all, or one per segment).
        P : array_like, optional
            Normal load at the vertices [N/m], positive; the first is the contact's ``P``, the
            load at which the contact is formed. None: the contact's constant ``P``.

        Examples
        --------
        >>> history = History.piecewise_linear([0, 100.0, -100.0], None, 4)
        >>> len(history), history.vertex_step.tolist(), history.Q[:3].tolist()
        (9, [0, 4, 8], [0.0, 25.0, 50.0])
        """
        Q = _loads("Q", Q)
        sigma = np.zeros_like(Q) if sigma is None else _loads("sigma", sigma)
        if Q.shape != sigma.shape:
            raise HistoryError(f"Q and sigma need one value per vertex, found {Q.size} and {sigma.size}")
        steps = np.broadcast_to(np.asarray(steps_per_segment), (Q.size - 1,))
        if steps.size and (not np.issubdtype(steps.dtype, np.integer) or np.any(steps < 1)):
            raise HistoryError(f"steps_per_segment must be integers >= 1, found {steps_per_segment!r}")
        if P is not None:
            P = _loads("P", P)
            if P.shape != Q.shape:
                raise HistoryError(f"Q and P need one value per vertex, found {Q.size} and {P.size}")
            P = _segments(P, steps)
        return cls(_segments(Q, steps), _segments(sigma, steps), np.concatenate([[0], np.cumsum(steps)]), None, P)

    @classmethod
    def sinusoidal(
        cls,
        Q_amplitude: float,
        sigma_amplitude: float = 0.0,
        phase_deg: float = 0.0,
        cycles: int = 1,
        steps_per_cycle: int = 64,
        Q_mean: float = 0.0,
        sigma_mean: float = 0.0,
        *,
        start: tuple[float, ...] = (0.0, 0.0),
        ramp_steps: int = RAMP_STEPS,
        P_amplitude: float = 0.0,
        P_mean: float | None = None,
        P_phase_deg: float = 0.0,
    ) -> History:
        """Sinusoidal load cycles, reached from `start` by a straight ramp when they start elsewhere.

        ``Q = Q_mean + Q_amplitude sin(theta)`` and ``sigma = sigma_mean + sigma_amplitude sin(theta + phase)``,
        ``theta`` from 0 to ``2 pi`` in each cycle: each cycle ends where it starts. From the unloaded
        state, the ramp leads to the means (and ``sigma_amplitude sin(phase)`` above them); its steps
        belong to no cycle.

        Parameters
        ----------
        Q_amplitude, sigma_amplitude : float
            Amplitudes [N/m], [Pa], >= 0.
        phase_deg : float
            Phase by which sigma leads Q [deg]: 0 in phase, 90 out of phase, 180 in opposition.
        cycles : int
            Number of cycles, >= 1.
        steps_per_cycle : int
            Equal increments of ``theta`` per cycle, >= 4; vertices are the cycle ends.
        Q_mean, sigma_mean : float
            Means [N/m], [Pa].
        start : tuple of float
            ``(Q, sigma)`` the history starts from [N/m], [Pa]; ``(Q, sigma, P)`` with a normal load.
        ramp_steps : int
            Steps of the ramp to the first point, >= 1.
        P_amplitude, P_mean, P_phase_deg : float
            A varying normal load ``P = P_mean + P_amplitude sin(theta + P_phase)`` [N/m], ``P_phase``
            [deg] by which it leads Q; `P_mean` None: no ``P`` column (the contact's constant ``P``).

        Examples
        --------
        >>> history = History.sinusoidal(1000.0, cycles=2, steps_per_cycle=8)
        >>> len(history), history.cycle_count, history.cycle.tolist()
        (17, 2, [0, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2])
        >>> bool(history.Q[0] == history.Q[8] == history.Q[16] == 0)  # each cycle ends where it starts
        True
        """
        amplitude, mean = _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean)
        phase = np.radians(_number("phase_deg", phase_deg))
        steps = _count("steps_per_cycle", steps_per_cycle, minimum=4)
        count = _count("cycles", cycles)
        n = count * steps + 1
        theta = np.remainder(np.arange(n, dtype=float), steps)
        theta *= 2 * np.pi
        theta /= steps  # 2 pi (k mod steps) / steps: exactly 0 again at each cycle end
        Q = _wave(theta, amplitude[0], mean[0])
        theta += phase
        sigma = _wave(theta, amplitude[1], mean[1])
        P = None
        if P_mean is not None:
            theta += np.radians(_number("P_phase_deg", P_phase_deg)) - phase
            P = _wave(theta, _number("P_amplitude", P_amplitude, 0.0), _number("P_mean", P_mean))
        del theta  # arrays of a long history are large (51 MB each for 10^5 cycles of 64 steps)
        waves = cls(Q, sigma, np.arange(0, n, steps), _cycle_numbers(n, steps), P)
        return _reached_from(start, waves, _count("ramp_steps", ramp_steps))

    @classmethod
    def random_amplitude(
        cls,
        cycles,
        Q_amplitude,
        sigma_amplitude=0.0,
        Q_mean=0.0,
        sigma_mean=0.0,
        seed=0,
        steps_per_segment=16,
        *,
        start=(0.0, 0.0),
        P_amplitude=0.0,
        P_mean=None,
    ):
        """Cycles of random amplitude: a straight rise to a peak, then a fall to a valley.

        Cycle ``k`` rises to ``Q_mean + u_k Q_amplitude`` and falls to ``Q_mean - v_k Q_amplitude``,
        sigma in phase with the same ``u_k`` and ``v_k``, drawn uniformly from [0, 1) by
        ``numpy.random.default_rng(seed)``. NumPy does not promise the same draws across its
        versions: keep the generated loads (a result holds them) rather than the seed.

        Parameters
        ----------
        cycles : int
            Number of cycles, >= 1.
        Q_amplitude, sigma_amplitude : float
            Largest excursions from the means [N/m], [Pa], >= 0.
        Q_mean, sigma_mean : float
            Means [N/m], [Pa].
        seed : int
            Seed of the generator, >= 0.
        steps_per_segment : int
            Equal increments of each rise and fall, >= 1.
        start : tuple of float
            ``(Q, sigma)`` the history starts from [N/m], [Pa]; the first rise starts there.
            ``(Q, sigma, P)`` with a normal load.
        P_amplitude, P_mean : float
            A varying normal load [N/m] in phase with Q (the same draws); `P_mean` None: no ``P``
            column (the contact's constant ``P``).
        """
        amplitude, mean = _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean)
        count = _count("cycles", cycles)
        steps = _count("steps_per_segment", steps_per_segment)
        excursion = (np.random.default_rng(_count("seed", seed, minimum=0)).random((count, 2)) * [1, -1]).ravel()
        start = _start(start)
        P = None
        if P_mean is not None:
            P_amplitude, P_mean = _number("P_amplitude", P_amplitude, 0.0), _number("P_mean", P_mean)
            P = np.concatenate([[start[2] if len(start) > 2 else P_mean], P_mean + P_amplitude * excursion])
        path = cls.piecewise_linear(
            np.concatenate([[start[0]], mean[0] + amplitude[0] * excursion]),
            np.concatenate([[start[1]], mean[1] + amplitude[1] * excursion]),
            steps,
            P,
        )
        return cls(path.Q, path.sigma, path.vertex_step, _cycle_numbers(len(path), 2 * steps), path.P)


def _cycle_numbers(n, steps):
    """Cycle numbers of `n` steps: 0 for step 0, then each cycle's number over its `steps` steps.

    Formed in place in 32 bits where ``n + steps`` fits (the History's own type), so a long
    history holds no 64-bit copy.
    """
    cycle = np.arange(n, dtype=np.int32 if n + steps <= CYCLE_LIMIT else np.int64)
    cycle += steps - 1
    cycle //= steps
    return cycle


def _reached_from(start, history, ramp_steps):
    """`history`, preceded by a straight ramp of `ramp_steps` steps from `start` if it starts elsewhere.

    A history of ``P`` starts from ``start[2]``, or at its own first ``P`` where `start` is a pair.
    """
    start = _start(start)
    P = None if history.P is None else (start[2] if len(start) > 2 else history.normal_start, history.normal_start)
    if history.start == start[:2] and (P is None or P[0] == P[1]):
        return history
    ramp = History.piecewise_linear(*zip(start[:2], history.start, strict=True), ramp_steps, P)
    return History.concatenate([ramp, history])


def _positives_decrease(cycle):
    """Whether any positive number of `cycle` is less than the positive one before it, checked
    `BLOCK_STEPS` steps at a time (a long history's cycle numbers are not copied whole)."""
    last = 0
    for start in range(0, cycle.size, BLOCK_STEPS):
        block = cycle[start : start + BLOCK_STEPS]
        positive = np.concatenate([[last], block[block > 0]])
        if np.any(positive[1:] < positive[:-1]):
            return True
        last = positive[-1]
    return False


def _bends(Q, sigma, kept, max_turn, units):
    """Steps where the path ``(Q / units[0], sigma / units[1])`` has turned by another `max_turn`
    [rad] from the first direction of its stretch, the steps from one `kept` step to the next.

    Increments that do not move have no direction and are passed over. On a straight stretch
    every direction is the first up to rounding, which `np.trunc` takes to no turn.
    """
    dQ, dsigma = np.diff(Q) / units[0], np.diff(sigma) / units[1]
    moving = np.flatnonzero((dQ != 0) | (dsigma != 0))
    direction = np.arctan2(dsigma[moving], dQ[moving])
    stretch = np.cumsum(kept)[moving]
    first = np.flatnonzero(np.diff(stretch, prepend=-1))  # the first moving increment of each stretch
    turn = direction - np.repeat(direction[first], np.diff(first, append=moving.size))
    turns = np.trunc((np.remainder(turn + np.pi, 2 * np.pi) - np.pi) / max_turn)
    return moving[1:][(turns[1:] != turns[:-1]) & (stretch[1:] == stretch[:-1])]


def _cycles(history):
    """Cycle numbers of every step, zeros for a history without cycles."""
    return np.zeros(len(history), dtype=np.int64) if history.cycle is None else history.cycle


def _wave(theta, amplitude, mean):
    """``mean + amplitude sin(theta)`` [N/m or Pa] for `theta` [rad], with no temporary array."""
    values = np.sin(theta)
    values *= amplitude
    values += mean
    return values


def _segments(vertices, steps):
    """Values along straight segments between `vertices`, ``steps[i]`` equal increments on segment ``i``.

    Each segment ends exactly on its vertex, and a segment between equal vertices holds that value
    exactly (an increment of one unit in the last place is a load change, which the exact model
    of Q alone slips under). The values of segment ``i`` are ``v_i + (v_(i+1) - v_i) (k / n)``,
    ``k = 1 .. n``, formed for all segments of one ``n`` at once in the output, so a history of
    millions of segments needs no array per segment; where all vertices are equal the values are
    one number broadcast to every step (`numpy.broadcast_to`, read-only), which takes no memory
    per step.
    """
    count = int(np.sum(steps)) + 1
    if np.all(vertices == vertices[0]):
        return np.broadcast_to(vertices[0], (count,))
    values = np.empty(count)
    values[0] = vertices[0]
    ends = np.cumsum(steps)
    for n in np.unique(steps):
        segment = np.flatnonzero(steps == n)
        uniform = segment.size == steps.size  # the output itself, one row per segment
        block = values[1:].reshape(-1, n) if uniform else np.empty((segment.size, n))
        np.multiply((vertices[segment + 1] - vertices[segment])[:, None], np.arange(1, n + 1) / n, out=block)
        block += vertices[segment, None]
        block[:, -1] = vertices[segment + 1]
        if not uniform:
            values[(ends[segment] - n)[:, None] + np.arange(1, n + 1)] = block
    return values


def _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean):
    """Validated amplitudes (>= 0) and means, each as a pair ``(Q, sigma)``."""
    amplitude = (_number("Q_amplitude", Q_amplitude, minimum=0.0), _number("sigma_amplitude", sigma_amplitude, 0.0))
    return amplitude, (_number("Q_mean", Q_mean), _number("sigma_mean", sigma_mean))


def _number(name, value, minimum=None):
    try:
        number = finite(name, value)
    except ValueError as error:
        raise HistoryError(str(error)) from None
    if minimum is not None and number < minimum:
        raise HistoryError(f"{name} must be >= {minimum}, found {value!r}")
    return number


def _count(name, value, minimum=1):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise HistoryError(f"{name} must be an integer >= {minimum}, found {value!r}")
    return int(value)


def _start(start):
    """``start`` as a tuple of floats ``(Q, sigma)``, or ``(Q, sigma, P)``."""
    values = _loads("start", start)
    if values.size not in (2, 3):
        raise HistoryError(f"start must be a pair (Q, sigma) or a triple (Q, sigma, P), found {start!r}")
    return tuple(float(value) for value in values)


def _normal_loads(P, n):
    """The normal loads `P` [N/m] of an `n`-step history: finite and positive at every step."""
    P = _loads("P", P)
    if P.shape != (n,):
        raise HistoryError(f"P must give one normal load per step, found {P.size} for {n} steps")
    lifted = np.flatnonzero(P <= 0)
    if lifted.size:
        step = int(lifted[0])
        raise HistoryError(f"P must stay positive (the contact lifts off): P = {float(P[step])!r} at step {step}")
    return P


def _loads(name, values):
    try:
        values = finite_array(name, values)
    except ValueError as error:
        raise HistoryError(str(error)) from None
    if values.size == 0:
        raise HistoryError(f"{name} is empty: a history needs at least its starting state")
    return values
