"""Method 4 by Gauss-Chebyshev collocation: the fixed grid of `Grid(nodes)`.

The slip is interpolated through its values at the ``N`` Gauss-Chebyshev points of ``t``; the
dislocation traction is then diagonal in the Chebyshev basis and the slip-to-traction matrix
is `fretting.models.solver.ChebyshevGrid`'s. The model's traction measure is
``sqrt(1 - t^2)`` times the traction [Pa].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fretting.models.base import ModelSpec
from fretting.models.method4 import Method4Model
from fretting.models.solver import ChebyshevGrid

if TYPE_CHECKING:
    from fretting.physics.contact import Contact

__all__ = ["DEFAULT_NODES", "CollocationModel", "Grid"]

#: Collocation nodes of `Grid()`: the closed forms of benchmarks/accuracy_vs_nodes.py within 1e-3
#: (stick-zone ends in a, traction in f p0, slip of its maximum) at this many nodes and not at 256.
DEFAULT_NODES = 384


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class Grid(ModelSpec):
    """Method 4 on the fixed grid of `nodes` Gauss-Chebyshev collocation points.

    Parameters
    ----------
    nodes : int
        Collocation points, at least 4.
    """

    nodes: int = DEFAULT_NODES

    name: ClassVar[str] = "grid"
    recorded_as: ClassVar[tuple[str, ...]] = (
        "method 4: dislocation correction to the fully adhered solution, Gauss-Chebyshev collocation",
    )
    description: ClassVar[str] = (
        "method 4: dislocation correction to the fully adhered solution, Gauss-Chebyshev collocation"
    )

    def __post_init__(self):
        if isinstance(self.nodes, bool) or not isinstance(self.nodes, (int, np.integer)) or self.nodes < 4:
            raise ValueError(f"nodes must be an integer >= 4, found {self.nodes!r}")

    @property
    def resolved(self) -> bool:
        return True

    def build(self, contact: Contact) -> CollocationModel:
        return CollocationModel(contact, self)

    def attributes(self) -> dict:
        return {"model": self.name, "nodes": int(self.nodes)}

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Grid:
        return cls(int(attrs["nodes"]))


class CollocationModel(Method4Model):
    """A contact discretised on Gauss-Chebyshev nodes.

    The discrete pressure is the contact's times `pressure_scale`, so that its quadrature
    carries ``P``: equilibrium on the grid is the quadrature ``Q = w sum g``, and the stick zone
    vanishes where ``|Q|`` reaches the friction force ``w sum limit``, which is then ``f P``. The
    Gauss-Chebyshev quadrature of ``p`` is exact where ``p sqrt(1 - t^2)`` is a polynomial of
    degree below ``2N`` (Hertz, the sharp flat punch); a rounded flat's pressure has a singular
    derivative at the flat's ends, where the unscaled quadrature falls short of ``P`` and loads
    just below ``f P`` would leave no stick zone.
    """

    theta = None

    def __init__(self, contact, spec):
        self.spec = spec
        self.contact = contact
        self.grid = ChebyshevGrid(spec.nodes)
        self.t = self.grid.t
        self.x = contact.centre + contact.a * self.t
        self.G = contact.E_star / contact.a * self.grid.stiffness
        self.w = contact.a * self.grid.weight  # quadrature weight of int F / sqrt(a^2 - x^2) dx times a
        weighted = contact.pressure_weighted(self.t)  # p sqrt(1 - t^2) [Pa]
        self.pressure_scale = contact.P / (self.w * weighted.sum())  # [-]
        self.limit = contact.f * self.pressure_scale * weighted  # f p sqrt(1 - t^2) of the discrete pressure [Pa]
        self.friction_force = self.w * self.limit.sum()  # f P to rounding [N/m]

    def g_stuck(self, Q, sigma):
        """``sqrt(1 - t^2) q_st`` [Pa], the fully stuck traction of eqs (9) and (20)."""
        a = self.contact.a
        return (Q / np.pi + sigma * a * self.t / 4) / a

    def traction(self, outcome):
        """The utilisation ``g / limit`` times the contact's ``f p`` [Pa].

        Coulomb's law then holds at the nodes against the contact's pressure, not only against
        the discrete one.
        """
        return outcome.g / (self.pressure_scale * np.sqrt(1 - self.t**2))

    def delta_Q(self, outcome):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] by the Gauss-Chebyshev rule."""
        return np.mean(outcome.slip, axis=-1)

    def delta_sigma(self, outcome):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] by the Gauss-Chebyshev rule.

        A row-wise sum, not a matrix product, so that a row's value does not depend on how
        many rows there are (a run split in parts equals the whole run bit for bit).
        """
        return self.w * np.sum(outcome.slip * self.t, axis=-1) / 4

    def dissipation(self, ds):
        """``int f p |ds| dx`` [J/m] of the discrete pressure."""
        return self.w * np.dot(self.limit, np.abs(ds))

    def dissipation_density(self, ds):
        """``f p |ds|`` [J/m^2] at the nodes, of the discrete pressure: its quadrature is `dissipation`."""
        return self.limit / np.sqrt(1 - self.t**2) * np.abs(ds)
