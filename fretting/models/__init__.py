"""Discretisations of the tangential problem behind one contract (`fretting.models.base`).

The specs a user picks a model with:

- `Exact`: the exact model of ``Q`` alone on a symmetric profile (Ciavarella-Jaeger with Masing's rule);
- `InPhase`: the exact model of in-phase ``Q`` and ``sigma`` on a Hertz contact (Nowell-Hills with Masing's rule);
- `Mesh`: method 4 by P1 Galerkin on a mesh in ``theta``, given or adapted to a relative accuracy;
- `Grid`: method 4 by Gauss-Chebyshev collocation on a fixed number of nodes;
- `Jaeger`: the exact model of a varying normal load ``P`` and ``Q`` without ``sigma`` on a symmetric contact that
  grows with the load (Jaeger's superposition);
- `Varying`: method 4 on cells fixed in ``x``, for a history that varies the normal load ``P``.
"""

from fretting.models.base import Model, ModelSpec, Outcome
from fretting.models.collocation import Grid
from fretting.models.exact import Exact
from fretting.models.galerkin import Mesh
from fretting.models.inphase import InPhase
from fretting.models.jaeger import Jaeger
from fretting.models.normal import Varying

__all__ = ["Exact", "Grid", "InPhase", "Jaeger", "Mesh", "Model", "ModelSpec", "Outcome", "Varying"]
