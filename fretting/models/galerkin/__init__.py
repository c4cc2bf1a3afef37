"""Method 4 of the seed paper by P1 Galerkin on a locally refinable mesh in ``theta``: the `Mesh` spec.


Positions in the contact are ``x = centre + a cos(theta)``, ``theta`` in ``[0, pi]``. The slip
``s(theta)`` is piecewise linear in ``theta`` on any mesh ``0 = theta_0 < ... < theta_M = pi``,
``s = sum_k s_k phi_k`` with hat functions ``phi_k``; both edge nodes are unknowns.

One topic a module: `kernels` (the stiffness, from the Clausen kernel of the elastic energy),
`quadrature` (the integrals of hats: loads, friction limits, the nodal recovery of the traction),
`model` (the spec `Mesh` and its `GalerkinModel`), `mesh` (element sizes that a history's zones ask
for, and refinement), `adaptation` (the mesh adapted to a history, run by the engine's loop).
"""

from fretting.models.galerkin.adaptation import MAX_TURN, adapted_model
from fretting.models.galerkin.kernels import clausen1, clausen3_complement, stiffness
from fretting.models.galerkin.mesh import (
    BOUNDARY_GRADING,
    BOUNDARY_SPAN,
    DEFAULT_RTOL,
    ENERGY_GRADING,
    ENERGY_SPAN,
    boundaries,
    boundary_fraction,
    element_targets,
    initial_theta,
    located_end,
    refine,
    tightened,
    uniform_theta,
    zone_fraction,
)
from fretting.models.galerkin.model import CAPPED, MAX_DEFAULT_MESH, MAX_DEFAULT_WORK, GalerkinModel, Mesh

__all__ = [
    "BOUNDARY_GRADING",
    "BOUNDARY_SPAN",
    "CAPPED",
    "MAX_DEFAULT_MESH",
    "MAX_DEFAULT_WORK",
    "DEFAULT_RTOL",
    "ENERGY_GRADING",
    "ENERGY_SPAN",
    "MAX_TURN",
    "GalerkinModel",
    "Mesh",
    "adapted_model",
    "boundaries",
    "boundary_fraction",
    "clausen1",
    "clausen3_complement",
    "element_targets",
    "initial_theta",
    "located_end",
    "refine",
    "stiffness",
    "tightened",
    "uniform_theta",
    "zone_fraction",
]
