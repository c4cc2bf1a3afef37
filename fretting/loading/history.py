"""Load histories: the shear force Q (or the tangential displacement delta), the bulk tension sigma and,
where it varies, the normal load P, at every step."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fretting._validate import array_in_unit, finite, finite_array, positive
from fretting.errors import HistoryError
from fretting.loading.loads import LoadBlock

__all__ = ["Formed", "History", "Joined", "Periodic", "PiecewiseLinear", "RAMP_STEPS"]

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
    delta : ndarray, shape (n_steps,), optional
        Tangential displacement of the pad relative to the specimen at the contact's datum [m]
        (docs/theory/displacement.md) where it is prescribed, NaN where ``Q`` is: each step
        prescribes exactly one of them (``Q`` is NaN where ``delta`` is given). None: ``Q`` at
        every step.
    """

    Q: np.ndarray
    sigma: np.ndarray
    vertex_step: np.ndarray
    cycle: np.ndarray | None = None
    P: np.ndarray | None = None
    delta: np.ndarray | None = None

    def __post_init__(self):
        Q, delta = (_loads("Q", self.Q), None) if self.delta is None else _prescribed(self.Q, self.delta)
        sigma = _loads("sigma", self.sigma, "Pa")
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
        if delta is not None:
            arrays["delta"] = delta
        for name, value in arrays.items():
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    def __len__(self):
        return self.Q.size

    def __getitem__(self, steps):
        """Contiguous steps ``history[start:stop]``, renumbered from 0, with their vertices and cycles.

        Cycle numbers are kept, so that a run continued from step ``k`` with ``history[k:]``
        numbers its cycles as the whole run does. The slice holds its loads (views of this
        history's arrays, or those formed for it by a `Formed` history).
        """
        if not isinstance(steps, slice) or steps.step not in (None, 1):
            raise TypeError(f"a History takes contiguous slices of steps, e.g. history[k:], found {steps!r}")
        start, stop, _ = steps.indices(len(self))
        if stop <= start:
            raise HistoryError(f"steps {start}:{stop} of a {len(self)}-step history are empty")
        inside = slice(*np.searchsorted(self.vertex_step, [start, stop]))  # vertex_step is sorted
        Q, sigma, cycle, P = self._steps(start, stop)
        delta = None if self.delta is None else self.delta[start:stop]
        return History(Q, sigma, self.vertex_step[inside] - start, cycle, P, delta)

    def _steps(self, start, stop):
        """``(Q, sigma, cycle, P)`` of the steps ``start .. stop - 1`` (views; cycle and P may be None)."""
        cycle = None if self.cycle is None else self.cycle[start:stop]
        P = None if self.P is None else self.P[start:stop]
        return self.Q[start:stop], self.sigma[start:stop], cycle, P

    def at(self, steps):
        """``(Q, sigma, cycle, P)`` at the steps `steps` (array of int): loads [N/m], [Pa], [N/m]
        and cycle numbers; cycle and P None where the history has none."""
        cycle = None if self.cycle is None else self.cycle[steps]
        P = None if self.P is None else self.P[steps]
        return self.Q[steps], self.sigma[steps], cycle, P

    def explicit(self):
        """This history with the loads of every step held in arrays: itself."""
        return self

    def moves(self, contact):
        """Names of the load inputs (`fretting.loading.loads.INPUTS`) this history moves on `contact`:
        ``Q`` and ``sigma`` always, ``P`` where it leaves the contact's, ``delta`` where it is
        prescribed (which the engine turns into ``Q``, `fretting.loading.loads.CONVERTED`)."""
        varies_P = self.P is not None and bool(np.any(self.P != contact.P))
        return frozenset(
            {"Q", "sigma"} | ({"P"} if varies_P else set()) | ({"delta"} if self.delta is not None else set())
        )

    @property
    def loads(self):
        """The loads of every step, a `LoadBlock` (``P`` None where the history does not vary it,
        ``delta`` None where it prescribes ``Q`` at every step)."""
        return LoadBlock(self.Q, self.sigma, self.P, self.delta)

    def displacements(self):
        """The same path with its ``Q`` read as the displacement ``delta`` [m] (``Q`` then NaN at every
        step): the history of a path of ``delta`` built as one of ``Q``."""
        Q, sigma, cycle, P = self.at(np.arange(len(self)))
        return History(np.full(len(self), np.nan), sigma, self.vertex_step, cycle, P, Q)

    @property
    def displaced(self):
        """True if some step prescribes the displacement ``delta`` rather than ``Q``."""
        return self.delta is not None

    @property
    def has_cycles(self):
        """True if the history counts load cycles (`cycle` is not None)."""
        return self.cycle is not None

    def cycle_ends(self):
        """Last step of each cycle, indexed by the cycle's number (1 .. `cycle_count`; entry 0 is unused)."""
        cycle = _cycles(self)
        runs = np.append(np.flatnonzero(cycle[1:] != cycle[:-1]), cycle.size - 1)  # the last step of each run
        return _last_steps(cycle[runs], runs, self.cycle_count)

    def without_P(self, P):
        """The history without its normal loads where they are `P` [N/m] at every step, else itself."""
        if self.P is None or not np.all(self.P == P):
            return self
        return History(self.Q, self.sigma, self.vertex_step, self.cycle, None, self.delta)

    @property
    def normal_start(self):
        """Normal load ``P`` at step 0 [N/m], None where the history does not vary it."""
        return self._loads_at(0)[1]

    @property
    def start(self):
        """Loads ``(Q, sigma)`` at step 0 [N/m], [Pa]."""
        return self._loads_at(0)[0]

    @property
    def end(self):
        """Loads ``(Q, sigma)`` at the last step [N/m], [Pa]."""
        return self._loads_at(len(self) - 1)[0]

    @property
    def normal_end(self):
        """Normal load ``P`` at the last step [N/m], None where the history does not vary it."""
        return self._loads_at(len(self) - 1)[1]

    def _loads_at(self, step):
        """``((Q, sigma), P)`` at `step` as floats, P None where the history does not vary it."""
        Q, sigma, _, P = self.at([step])
        return (float(Q[0]), float(sigma[0])), None if P is None else float(P[0])

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

    def largest_loads(self):
        """``(max |Q|, max |sigma|)`` [N/m], [Pa] over every step, taken `BLOCK_STEPS` steps at a time."""
        largest = np.zeros(2)
        for block in self.blocks():
            np.maximum(largest, [np.abs(load).max() for load in block], out=largest)
        return float(largest[0]), float(largest[1])

    def first_step(self, condition):
        """First step where ``condition(Q, sigma)`` (a boolean array of the loads of a block) holds; None if none.

        Taken `BLOCK_STEPS` steps at a time, with no temporary array of the whole history.
        """
        for start, (Q, sigma) in zip(range(0, len(self), BLOCK_STEPS), self.blocks(), strict=True):
            found = np.flatnonzero(condition(Q, sigma))
            if found.size:
                return start + int(found[0])
        return None

    def blocks(self):
        """``(Q, sigma)`` [N/m], [Pa] of `BLOCK_STEPS` steps at a time, in order (views of an explicit
        history's arrays, formed for the block by a `Formed` history).

        A pass over a long history block by block makes temporary arrays of one block, not of
        the whole history.
        """
        for start in range(0, len(self), BLOCK_STEPS):
            yield self._steps(start, min(start + BLOCK_STEPS, len(self)))[:2]

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
        Q, sigma, cycle, P = self.at(steps)
        return History(Q, sigma, np.searchsorted(steps, self.vertex_step), cycle, P)

    def as_cycle(self):
        """The same path counted as one load cycle: every step after the first belongs to cycle 1."""
        cycle = np.ones(len(self), dtype=np.int64)
        cycle[0] = 0
        return History(self.Q, self.sigma, self.vertex_step, cycle, self.P, self.delta)

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
        if len({history.normal_start is None for history in histories}) > 1:
            raise HistoryError("histories with a normal load P and without one cannot be concatenated")
        if len({history.displaced for history in histories}) > 1:
            raise HistoryError("histories of Q and histories of delta cannot be concatenated (not yet)")
        for number, (previous, history) in enumerate(itertools.pairwise(histories), start=2):
            if _point(history, 0) != _point(previous, len(previous) - 1):
                raise HistoryError(
                    f"history {number} starts at {_point(history, 0)}, "
                    f"expected the end of the previous one, {_point(previous, len(previous) - 1)}"
                )
        if histories[0].displaced:
            return _joined_explicit(histories)
        if all(isinstance(history, PiecewiseLinear) for history in histories):
            return PiecewiseLinear.joined(histories)
        joined = Joined(histories)
        return joined if any(isinstance(history, Formed) for history in histories) else joined.explicit()

    @classmethod
    def piecewise_linear(
        cls,
        Q: ArrayLike | None = None,
        sigma: ArrayLike | None = None,
        steps_per_segment: int | ArrayLike = 16,
        P: ArrayLike | None = None,
        *,
        delta: ArrayLike | None = None,
    ) -> History:
        """Straight segments between vertices of the (Q, sigma) path, or of the (P, Q, sigma) path;
        with `delta` instead of `Q`, of the (delta, sigma) path (displacement control).

        Parameters
        ----------
        Q : array_like
            Shear force at the vertices [N/m]; the first vertex is the starting state.
            Not with `delta`.
        sigma : array_like, optional
            Bulk tension at the vertices [Pa]; zero when omitted.
        steps_per_segment : int or array_like of int
            Equal increments of each segment (one number for all, or one per segment).
        P : array_like, optional
            Normal load at the vertices [N/m], positive; the first is the contact's ``P``, the
            load at which the contact is formed. None: the contact's constant ``P``.
        delta : array_like, optional
            Tangential displacement of the pad relative to the specimen at the contact's datum at
            the vertices [m] (docs/theory/displacement.md), prescribed instead of `Q`: each step
            solves for its ``Q`` (`fretting.engine.follow.displaced`).

        Examples
        --------
        >>> history = History.piecewise_linear([0, 100.0, -100.0], None, 4)
        >>> len(history), history.vertex_step.tolist(), history.Q[:3].tolist()
        (9, [0, 4, 8], [0.0, 25.0, 50.0])
        >>> moved = History.piecewise_linear(delta=[0, 1e-6], steps_per_segment=2)
        >>> moved.delta.tolist(), bool(np.isnan(moved.Q).all())
        ([0.0, 5e-07, 1e-06], True)
        """
        if (Q is None) == (delta is None):
            raise HistoryError(
                "give the vertices of either Q or delta, found " + ("both" if Q is not None else "neither")
            )
        if delta is None:
            return PiecewiseLinear.through(Q, sigma, steps_per_segment, P).explicit()
        delta = _loads("delta", delta, "m")  # in m here: `through` takes its vertices as those of Q
        return PiecewiseLinear.through(delta, sigma, steps_per_segment, P).explicit().displacements()

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
        by_cycle: bool = False,
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
        by_cycle : bool
            Return the history held by one cycle (`Periodic`, after its ramp: loads formed when
            read, memory of one cycle whatever the count) rather than by the loads of its steps.

        Examples
        --------
        >>> history = History.sinusoidal(1000.0, cycles=2, steps_per_cycle=8)
        >>> len(history), history.cycle_count, history.cycle.tolist()
        (17, 2, [0, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2])
        >>> bool(history.Q[0] == history.Q[8] == history.Q[16] == 0)  # each cycle ends where it starts
        True
        """
        amplitude, mean = _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean)
        phase = np.radians(_number("phase_deg", phase_deg, unit="deg"))
        steps = _count("steps_per_cycle", steps_per_cycle, minimum=4)
        theta = np.remainder(np.arange(steps + 1, dtype=float), steps)
        theta *= 2 * np.pi
        theta /= steps  # 2 pi (k mod steps) / steps: exactly 0 again at the cycle's end
        Q = _wave(theta, amplitude[0], mean[0])
        theta += phase
        sigma = _wave(theta, amplitude[1], mean[1])
        P = None
        if P_mean is not None:
            theta += np.radians(_number("P_phase_deg", P_phase_deg, unit="deg")) - phase
            P = _wave(theta, _number("P_amplitude", P_amplitude, 0.0, "N/m"), _number("P_mean", P_mean, unit="N/m"))
        waves = Periodic(History(Q, sigma, [0, steps], None, P), _count("cycles", cycles))
        history = _reached_from(start, waves, _count("ramp_steps", ramp_steps))
        return history if by_cycle else history.explicit()

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
        vertices=False,
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
        vertices : bool
            Return the history held by its vertices (`PiecewiseLinear`, whose loads are formed
            when read: memory per vertex, not per step) rather than by the loads of its steps.
        """
        amplitude, mean = _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean)
        count = _count("cycles", cycles)
        steps = _count("steps_per_segment", steps_per_segment)
        excursion = (np.random.default_rng(_count("seed", seed, minimum=0)).random((count, 2)) * [1, -1]).ravel()
        start = _start(start)
        P = None
        if P_mean is not None:
            P_amplitude, P_mean = _number("P_amplitude", P_amplitude, 0.0, "N/m"), _number("P_mean", P_mean, unit="N/m")
            P = np.concatenate([[start[2] if len(start) > 2 else P_mean], P_mean + P_amplitude * excursion])
        path = PiecewiseLinear.through(
            np.concatenate([[start[0]], mean[0] + amplitude[0] * excursion]),
            np.concatenate([[start[1]], mean[1] + amplitude[1] * excursion]),
            steps,
            P,
        )
        cycle = np.arange(2 * count, dtype=np.int64) // 2 + 1  # a rise and a fall each
        held = PiecewiseLinear(path.vertex_Q, path.vertex_sigma, path.steps, cycle, path.vertex_P)
        return held if vertices else held.explicit()


class Formed(History):
    """A history held by a compact description, whose loads are formed when they are read.

    A subclass gives `__len__`, `at`, `vertex_step`, `has_cycles`, `cycle_count` and
    `cycle_ends`; every step, slice (`__getitem__`), block and whole array of it is then formed
    by its `at`, so they are bit for bit the loads of `explicit`, and a long history costs
    memory by its description and by the block read, not by its steps.

    Reading `Q`, `sigma`, `cycle` or `P` forms the array of every step anew: a pass over a long
    history reads it by `blocks`, slices or `at`.
    """

    @property
    def Q(self):
        """Shear force at every step [N/m], formed anew."""
        return self._whole(0)[0]

    @property
    def sigma(self):
        """Bulk tension at every step [Pa], formed anew."""
        return self._whole(1)[0]

    @property
    def cycle(self):
        """Cycle number (int32) of every step, formed anew; None for a history without cycles."""
        return self._whole(2)[0] if self.has_cycles else None

    @property
    def P(self):
        """Normal load at every step [N/m], formed anew; None: the contact's constant ``P``."""
        return None if self.normal_start is None else self._whole(3)[0]

    def _whole(self, *items):
        """Items `items` of `at` (0 Q, 1 sigma, 2 cycle, 3 P) at every step, formed together in one pass
        `BLOCK_STEPS` steps at a time; None for an item that `at` gives as None."""
        wholes = [None] * len(items)
        for start in range(0, len(self) if items else 0, BLOCK_STEPS):
            steps = np.arange(start, min(start + BLOCK_STEPS, len(self)))
            blocks = self.at(steps)
            for k, item in enumerate(items):
                if blocks[item] is not None:
                    if wholes[k] is None:
                        wholes[k] = np.empty(len(self), dtype=blocks[item].dtype)
                    wholes[k][steps] = blocks[item]
        return wholes

    def _steps(self, start, stop):
        return self.at(np.arange(start, stop))

    def explicit(self):
        """The same history as a `History` whose arrays hold the loads of every step."""
        Q, sigma, cycle, P = self._whole(0, 1, 2, 3)
        return History(Q, sigma, self.vertex_step, cycle, P)

    def turning_steps(self, max_turn=None, units=(1.0, 1.0)):
        """`History.turning_steps`, taken over slices of about `BLOCK_STEPS` steps from vertex to vertex.

        Every vertex is a turning step, and whether a step inside a slice turns depends on the
        steps of its stretch (from one turning step to the next) only, all inside the slice: the
        slices' turning steps are the whole history's.
        """
        if max_turn is not None:
            positive("max_turn", max_turn)
        last = len(self) - 1
        cuts = self.vertex_step[np.searchsorted(self.vertex_step, np.arange(BLOCK_STEPS, last, BLOCK_STEPS))]
        cuts = np.unique(np.concatenate([[0], cuts, [last]]))
        parts = [self[a : b + 1].turning_steps(max_turn, units) + a for a, b in itertools.pairwise(cuts)]
        return np.unique(np.concatenate([[0], *parts]))


class PiecewiseLinear(Formed):
    """A history of straight segments between vertices, held by its vertices: the loads of any
    steps are formed when they are read (`Formed`).

    The loads of segment ``i`` at its steps ``k = 1 .. n_i`` are ``v_i + (v_(i+1) - v_i) (k / n_i)``,
    the last exactly ``v_(i+1)`` (an increment of one unit in the last place is a load change,
    which the exact model of Q alone slips under), and a load whose vertices are all equal is that
    number at every step. A long history costs memory per vertex (about 40 bytes).

    Parameters
    ----------
    vertex_Q, vertex_sigma : array_like, shape (n_vertices,)
        Loads at the vertices [N/m], [Pa]; the first is step 0.
    steps : array_like of int, shape (n_vertices - 1,)
        Equal increments of each segment, >= 1.
    segment_cycle : array_like of int, shape (n_vertices - 1,), optional
        Load cycle of the steps of each segment (0: none), non-zero ones non-decreasing; step 0
        belongs to no cycle. None for a history without cycles.
    vertex_P : array_like, shape (n_vertices,), optional
        Normal loads at the vertices [N/m], positive. None: the contact's constant ``P``.
    """

    def __init__(self, vertex_Q, vertex_sigma, steps, segment_cycle=None, vertex_P=None):
        arrays = {"vertex_Q": _loads("Q", vertex_Q), "vertex_sigma": _loads("sigma", vertex_sigma, "Pa")}
        arrays["steps"] = np.asarray(steps, dtype=np.int64)
        if arrays["vertex_sigma"].shape != arrays["vertex_Q"].shape or arrays["steps"].shape != (
            arrays["vertex_Q"].size - 1,
        ):
            raise HistoryError("vertex_Q and vertex_sigma need one value per vertex and steps one per segment")
        if np.any(arrays["steps"] < 1):
            raise HistoryError("steps must be integers >= 1, one per segment")
        arrays["vertex_step"] = np.concatenate([[0], np.cumsum(arrays["steps"])])
        arrays["segment_cycle"] = None if segment_cycle is None else _segment_cycles(segment_cycle, arrays["steps"])
        arrays["vertex_P"] = None if vertex_P is None else _loads("P", vertex_P)
        if arrays["vertex_P"] is not None and arrays["vertex_P"].shape != arrays["vertex_Q"].shape:
            raise HistoryError("vertex_P needs one value per vertex")
        for name, value in arrays.items():
            if value is not None:
                value.setflags(write=False)
            object.__setattr__(self, name, value)
        if self.vertex_P is not None and np.any(self.vertex_P <= 0):  # first reached inside the segment before
            vertex = int(np.flatnonzero(self.vertex_P <= 0)[0])
            steps = np.arange(self.vertex_step[max(vertex - 1, 0)], self.vertex_step[vertex] + 1)
            P = self._formed(self.vertex_P, steps, self._segments(steps))
            lifted = np.flatnonzero(P <= 0)[0]
            raise _lift_off(P[lifted], steps[lifted])

    def __repr__(self):
        return f"PiecewiseLinear({len(self)} steps, {self.vertex_Q.size} vertices, {self.cycle_count} cycles)"

    def __len__(self):
        return int(self.vertex_step[-1]) + 1

    @property
    def has_cycles(self):
        return self.segment_cycle is not None

    @property
    def cycle_count(self):
        return 0 if self.segment_cycle is None else int(self.segment_cycle.max(initial=0))

    def at(self, steps):
        steps = np.asarray(steps, dtype=np.int64)
        segment = self._segments(steps)
        cycle = (
            None if self.segment_cycle is None else np.where(steps > 0, self.segment_cycle[segment], 0).astype(np.int32)
        )
        P = None if self.vertex_P is None else self._formed(self.vertex_P, steps, segment)
        return self._formed(self.vertex_Q, steps, segment), self._formed(self.vertex_sigma, steps, segment), cycle, P

    def cycle_ends(self):
        return _last_steps(self.segment_cycle, self.vertex_step[1:], self.cycle_count)

    def without_P(self, P):
        if self.vertex_P is None or not np.all(self.vertex_P == P):
            return self
        return PiecewiseLinear(self.vertex_Q, self.vertex_sigma, self.steps, self.segment_cycle)

    def as_cycle(self):
        return PiecewiseLinear(
            self.vertex_Q, self.vertex_sigma, self.steps, np.ones(self.steps.size, dtype=np.int32), self.vertex_P
        )

    def _whole(self, *items):
        """`Formed._whole`, without an array where a load's vertices are all equal (a read-only broadcast)."""
        vertices = {0: self.vertex_Q, 1: self.vertex_sigma, 3: self.vertex_P}
        constant = {item: vertices[item][0] for item in items if _constant(vertices.get(item))}
        formed = iter(super()._whole(*(item for item in items if item not in constant)))
        return [np.broadcast_to(constant[item], (len(self),)) if item in constant else next(formed) for item in items]

    def _segments(self, steps):
        """The segment of each of `steps` (array of int): the one that ends at or after it (0 at step 0).

        Searched among the vertices from the first step's to the last step's only: a chunk of a long
        history lies among a few of its vertices.
        """
        if steps.size == 0:
            return np.zeros(0, dtype=np.int64)
        low, high = np.searchsorted(self.vertex_step, [steps.min(), steps.max()])
        return np.maximum(np.searchsorted(self.vertex_step[low : high + 1], steps) + (low - 1), 0)

    def _formed(self, vertices, steps, segment):
        """Loads of one load's `vertices` at `steps` (array of int) in their `segment`s: the class's formula."""
        if _constant(vertices):
            return np.full(steps.shape, vertices[0])
        k, n = steps - self.vertex_step[segment], self.steps[segment]
        values = vertices[segment + 1] - vertices[segment]
        values *= k / n
        values += vertices[segment]
        np.copyto(values, vertices[segment + 1], where=k == n)  # each segment ends exactly on its vertex
        np.copyto(values, vertices[0], where=steps == 0)
        return values

    @classmethod
    def joined(cls, histories):
        """`History.concatenate` of piecewise-linear `histories`, already checked to follow one another."""
        first, later = histories[0], histories[1:]
        loads = [
            np.concatenate([getattr(first, name), *(getattr(history, name)[1:] for history in later)])
            for name in ("vertex_Q", "vertex_sigma")
        ]
        P = None
        if first.vertex_P is not None:
            P = np.concatenate([first.vertex_P, *(history.vertex_P[1:] for history in later)])
        cycles, counted = [], 0
        for history in histories:
            own = np.zeros(history.steps.size, np.int64) if history.segment_cycle is None else history.segment_cycle
            cycles.append(np.where(own > 0, own + counted, 0))
            counted += history.cycle_count
        has_cycles = any(history.has_cycles for history in histories)
        steps = np.concatenate([history.steps for history in histories])
        return cls(*loads, steps, np.concatenate(cycles) if has_cycles else None, P)

    @classmethod
    def through(cls, Q, sigma=None, steps_per_segment=16, P=None):
        """`History.piecewise_linear`'s history, held by its vertices (the same parameters)."""
        Q = _loads("Q", Q)
        sigma = np.zeros_like(Q) if sigma is None else _loads("sigma", sigma, "Pa")
        if Q.shape != sigma.shape:
            raise HistoryError(f"Q and sigma need one value per vertex, found {Q.size} and {sigma.size}")
        steps = np.broadcast_to(np.asarray(steps_per_segment), (Q.size - 1,))
        if steps.size and (not np.issubdtype(steps.dtype, np.integer) or np.any(steps < 1)):
            raise HistoryError(f"steps_per_segment must be integers >= 1, found {steps_per_segment!r}")
        if P is not None:
            P = _loads("P", P)
            if P.shape != Q.shape:
                raise HistoryError(f"Q and P need one value per vertex, found {Q.size} and {P.size}")
        return cls(Q, sigma, steps, None, P)


class Periodic(Formed):
    """`count` repetitions of one load cycle, held by that cycle's loads (`Formed`): memory per
    step of one cycle, whatever the count.

    Step ``k >= 1`` has the loads of the cycle's step ``(k - 1) mod n + 1`` (``n`` its
    increments) and belongs to cycle ``(k - 1) // n + 1``; step 0 has the cycle's first loads,
    which its last ones repeat (the path is closed). The vertices are the cycles' ends.

    Parameters
    ----------
    cycle : History
        One cycle, its step 0 the loads it starts and ends at; its own vertices and cycle
        numbers are not used.
    count : int
        Number of cycles, >= 1.
    """

    def __init__(self, cycle, count):
        if (cycle.start, cycle.normal_start) != (cycle.end, cycle.normal_end) or len(cycle) < 2:
            raise HistoryError(f"a periodic history repeats a closed cycle, not one from {cycle.start} to {cycle.end}")
        object.__setattr__(self, "one", cycle)
        object.__setattr__(self, "count", _count("count", count))
        object.__setattr__(self, "period", len(cycle) - 1)
        object.__setattr__(self, "vertex_step", np.arange(0, self.count * self.period + 1, self.period))

    def __repr__(self):
        return f"Periodic({self.count} cycles of {self.period} steps)"

    def __len__(self):
        return self.count * self.period + 1

    has_cycles = True

    @property
    def cycle_count(self):
        return self.count

    def at(self, steps):
        steps = np.asarray(steps, dtype=np.int64)
        cycle, phase = np.divmod(np.maximum(steps - 1, 0), self.period)
        cycle += 1
        phase += 1
        first = steps == 0
        cycle[first] = phase[first] = 0
        Q, sigma, _, P = self.one.at(phase)
        return Q, sigma, cycle.astype(np.int32), P

    def cycle_ends(self):
        return self.vertex_step

    def without_P(self, P):
        one = self.one.without_P(P)
        return self if one is self.one else Periodic(one, self.count)


class Joined(Formed):
    """Histories one after the other (`History.concatenate`), held by them (`Formed`).

    Parameters
    ----------
    histories : sequence of History
        Each starting exactly where the previous one ends (checked by `History.concatenate`);
        the step 0 of each after the first, which repeats that point, is dropped. Cycles are
        counted on: those of each history are numbered after the previous ones.
    """

    def __init__(self, histories):
        parts = tuple(histories)
        ends = np.cumsum([len(parts[0]) - 1] + [len(history) - 1 for history in parts[1:]])
        object.__setattr__(self, "parts", parts)
        object.__setattr__(self, "ends", ends)  # the last step of each part
        object.__setattr__(self, "starts", np.concatenate([[0], ends[:-1]]))  # the step each part starts at
        object.__setattr__(self, "counted", np.cumsum([0] + [history.cycle_count for history in parts[:-1]]))
        object.__setattr__(self, "vertex_step", _joined_vertices(parts, ends))
        object.__setattr__(self, "varies_P", parts[0].normal_start is not None)
        object.__setattr__(self, "cycled", any(history.has_cycles for history in parts))

    def __repr__(self):
        return f"Joined({len(self)} steps, {len(self.parts)} histories, {self.cycle_count} cycles)"

    def __len__(self):
        return int(self.ends[-1]) + 1

    @property
    def has_cycles(self):
        return self.cycled

    @property
    def cycle_count(self):
        return int(self.counted[-1]) + self.parts[-1].cycle_count

    def at(self, steps):
        steps = np.asarray(steps, dtype=np.int64)
        part = np.searchsorted(self.ends, steps)  # the first part that ends at or after each step
        first, last = (int(part.min()), int(part.max())) if part.size else (0, 0)
        if first == last:
            return self._part_at(first, steps)
        loads = (np.empty(steps.shape), np.empty(steps.shape), np.empty(steps.shape, np.int32), np.empty(steps.shape))
        for index in range(first, last + 1):
            here = part == index
            for whole, piece in zip(loads, self._part_at(index, steps[here]), strict=True):
                if piece is not None:
                    whole[here] = piece
        return loads[0], loads[1], loads[2] if self.cycled else None, loads[3] if self.varies_P else None

    def _part_at(self, index, steps):
        """`at` of `steps` of this history that all lie in part `index`, its cycles counted on."""
        Q, sigma, own, P = self.parts[index].at(steps - self.starts[index])
        if not self.cycled:
            return Q, sigma, None, P
        cycle = np.zeros(steps.shape, np.int32) if own is None else own
        np.add(cycle, self.counted[index], out=cycle, where=cycle > 0)
        return Q, sigma, cycle, P

    def cycle_ends(self):
        parts = zip(self.parts, self.starts, strict=True)
        return np.concatenate([[0], *(part.cycle_ends()[1:] + start for part, start in parts if part.has_cycles)])

    def without_P(self, P):
        parts = [history.without_P(P) for history in self.parts]
        return self if any(part.normal_start is not None for part in parts) else Joined(parts)


def _joined_vertices(histories, ends):
    """Vertex steps of `histories` one after the other, each ending at `ends`: a vertex at a
    history's step 0 is dropped where the previous one ends on a vertex."""
    vertex_step, last_vertex = [histories[0].vertex_step], histories[0].vertex_step.max(initial=-1)
    for end, history in zip(ends[:-1], histories[1:], strict=True):  # each part starts where the one before ends
        vertices = history.vertex_step[history.vertex_step > 0] if last_vertex == end else history.vertex_step
        vertex_step.append(vertices + end)
        last_vertex = vertices[-1] + end if vertices.size else last_vertex
    return np.concatenate(vertex_step)


def _point(history, step):
    """The loads of `history` at `step` as text: ``(Q, sigma)`` or ``(delta, sigma)``, and ``P``."""
    if history.displaced:
        return (
            f"(delta, sigma) = {(float(history.delta[step]), float(history.sigma[step]))}, P = {history.normal_start}"
        )
    (Q, sigma), P = history._loads_at(step)
    return f"(Q, sigma) = {(Q, sigma)}, P = {P}"


def _joined_explicit(histories):
    """`History.concatenate` of explicit `histories` already checked to follow one another: their
    arrays joined, the step 0 of each after the first dropped, cycles counted on."""
    first = [0] + [1] * (len(histories) - 1)  # the first step each contributes
    offset = np.cumsum([0] + [len(history) - 1 for history in histories[:-1]])

    def joined(name):
        if getattr(histories[0], name) is None:
            return None
        return np.concatenate([getattr(history, name)[k:] for history, k in zip(histories, first, strict=True)])

    cycles, counted = [], 0
    for history, k in zip(histories, first, strict=True):
        own = _cycles(history)[k:]
        cycles.append(np.where(own > 0, own + counted, 0))
        counted += history.cycle_count
    vertex_step = np.unique(np.concatenate([h.vertex_step + o for h, o in zip(histories, offset, strict=True)]))
    cycle = np.concatenate(cycles) if any(history.has_cycles for history in histories) else None
    return History(joined("Q"), joined("sigma"), vertex_step, cycle, joined("P"), joined("delta"))


def _constant(vertices):
    """True where `vertices` (or None) are the loads of a load that keeps one value."""
    return vertices is not None and bool(np.all(vertices == vertices[0]))


def _segment_cycles(segment_cycle, steps):
    """`segment_cycle` checked (>= 0, at most `CYCLE_LIMIT`, non-zero ones non-decreasing) as int32."""
    cycle = np.asarray(segment_cycle)
    if cycle.shape != steps.shape or not np.issubdtype(cycle.dtype, np.integer) or np.any(cycle < 0):
        raise HistoryError("segment_cycle must give a cycle number >= 0 for every segment")
    if cycle.size and cycle.max() > CYCLE_LIMIT:
        raise HistoryError(f"cycle numbers must be at most {CYCLE_LIMIT}, found {cycle.max()}")
    cycle = cycle.astype(np.int32)
    if _positives_decrease(cycle):
        raise HistoryError("segment_cycle must give cycle numbers >= 0, non-zero ones non-decreasing")
    return cycle


def _last_steps(numbers, steps, count):
    """Last step of each cycle ``0 .. count`` among `steps` (the last of runs or segments of cycle `numbers`)."""
    ends = np.zeros(count + 1, dtype=np.int64)
    np.maximum.at(ends, numbers, steps)
    return ends


def _reached_from(start, history, ramp_steps):
    """`history`, preceded by a straight ramp of `ramp_steps` steps from `start` if it starts elsewhere.

    A history of ``P`` starts from ``start[2]``, or at its own first ``P`` where `start` is a pair.
    """
    start = _start(start)
    first = history.normal_start
    P = None if first is None else (start[2] if len(start) > 2 else first, first)
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


def _amplitudes_means(Q_amplitude, sigma_amplitude, Q_mean, sigma_mean):
    """Validated amplitudes (>= 0) and means, each as a pair ``(Q, sigma)``."""
    amplitude = (
        _number("Q_amplitude", Q_amplitude, 0.0, "N/m"),
        _number("sigma_amplitude", sigma_amplitude, 0.0, "Pa"),
    )
    return amplitude, (_number("Q_mean", Q_mean, unit="N/m"), _number("sigma_mean", sigma_mean, unit="Pa"))


def _number(name, value, minimum=None, unit="1"):
    """`value` (a number, or a quantity converted to `unit`) as a finite float, at least `minimum`."""
    try:
        number = finite(name, value, unit)
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
    """``start`` as a tuple of floats ``(Q, sigma)`` [N/m], [Pa], or ``(Q, sigma, P)`` [N/m, Pa, N/m]."""
    if not isinstance(start, (list, tuple, np.ndarray)) or len(start) not in (2, 3):
        raise HistoryError(f"start must be a pair (Q, sigma) or a triple (Q, sigma, P), found {start!r}")
    return tuple(
        _number(f"start[{k}]", value, unit=unit)
        for k, (value, unit) in enumerate(zip(start, _START_UNITS[: len(start)], strict=True))
    )


#: Units of the loads of a `start` tuple ``(Q, sigma, P)``.
_START_UNITS = ("N/m", "Pa", "N/m")


def _normal_loads(P, n):
    """The normal loads `P` [N/m] of an `n`-step history: finite and positive at every step."""
    P = _loads("P", P)
    if P.shape != (n,):
        raise HistoryError(f"P must give one normal load per step, found {P.size} for {n} steps")
    lifted = np.flatnonzero(P <= 0)
    if lifted.size:
        raise _lift_off(P[lifted[0]], lifted[0])
    return P


def _lift_off(P, step):
    """The error of a normal load `P` [N/m] <= 0 at `step`."""
    return HistoryError(f"P must stay positive (the contact lifts off): P = {float(P)!r} at step {int(step)}")


def _prescribed(Q, delta):
    """`Q` [N/m] and `delta` [m] of a history, checked: each step prescribes exactly one of them
    (a finite number), the other NaN there."""
    try:
        Q, delta = array_in_unit("Q", Q, "N/m"), array_in_unit("delta", delta, "m")
    except ValueError as error:
        raise HistoryError(str(error)) from None
    if Q.ndim != 1 or Q.shape != delta.shape or Q.size == 0:
        raise HistoryError(f"Q and delta must give one value per step, found {Q.size} and {delta.size}")
    for name, values in (("Q", Q), ("delta", delta)):
        if np.any(np.isinf(values)):
            raise HistoryError(f"{name} must be finite, found {values[np.isinf(values)][0]!r}")
    for found, problem in (
        (~np.isnan(Q) & ~np.isnan(delta), "both Q and delta"),
        (np.isnan(Q) & np.isnan(delta), "neither Q nor delta"),
    ):
        if found.any():
            raise HistoryError(f"step {int(np.argmax(found))} gives {problem}, expected exactly one of them")
    return Q, delta


def _loads(name, values, unit="N/m"):
    """`values` of the load `name` (numbers in `unit` (SI), or quantities converted to it) as a
    non-empty 1-D float array of finite numbers."""
    try:
        values = finite_array(name, values, unit=unit)
    except ValueError as error:
        raise HistoryError(str(error)) from None
    if values.size == 0:
        raise HistoryError(f"{name} is empty: a history needs at least its starting state")
    return values
