"""Energy of small load changes on a large locked-in slip: the default mesh against its laws (issue 18).

A Hertzian contact (the tests' contact) is loaded to ``Q0 = 0.3 f P`` (and ``sigma0 = 0.2 f p0``
where sigma is held) and then cycled with small amplitudes ``A``; at each amplitude:

- reversal: one unloading increment of ``A f P`` after loading to ``0.5 f P`` under Q alone, on
  the default Galerkin mesh (``rtol=DEFAULT_RTOL``) against the exact model (Mindlin-Deresiewicz):
  ``W / W_exact - 1``;
- Q cycles, sigma held: the energy ``W`` of the second of two cycles of ``Q0 +- A f P``, printed as
  ``W / A^3`` (a small loop at the edges of the contact dissipates as the cube of its amplitude),
  at default settings and at ``FINE_RTOL``, and their relative difference;
- sigma cycles, Q held: the same for cycles of ``sigma0 +- A f p0``, printed as ``W / A`` (the
  tension drives the slip zones at the two edges on in turn, each by the amplitude).

Then the energy of the last of two cycles of ``Q`` and ``sigma`` 90 degrees apart, of amplitude
``1e-4 f P`` and ``1e-4 f p0`` about the same loads, at default settings and at finer rtol
(the reference of tests/test_trajectories.py::test_energy_of_small_cycles_on_a_locked_in_slip,
rtol = `ELLIPSE_RTOLS` [1], and its convergence), each with its nodes and CPU time.

Below some amplitude a cycle's traction changes by less than the solver's rounding allowance
(`fretting.models.solver.ROUNDING` of the largest term of the traction, ``|G| |slip|`` of the
locked-in slip) and the cycle dissipates nothing; a ``*`` marks the rows where the default's
dataset says that some increments fall below that floor (``model_fallback``).

Run:  python benchmarks/small_loops.py
"""

import time
import warnings

import numpy as np

import fretting as fr
from fretting.physics.contact import plane_strain_modulus

AMPLITUDES = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)


def hertz():
    """R = 50 mm, E = 210 GPa, nu = 0.3, f = 0.6, P = 100 N/mm (the tests' contact)."""
    return fr.Contact(fr.Hertz(0.05), plane_strain_modulus(210e9, 0.3), 0.6, 1e5)


def reversal(contact, A):
    """``W_mesh / W_exact - 1`` of one unloading increment of ``A f P`` from ``0.5 f P``."""
    history = fr.History.piecewise_linear(np.array([0, 0.5, 0.5 - A]) * contact.f * contact.P, None, [4, 1])
    exact = fr.simulate(contact, history).dissipation.values[-1]
    mesh = fr.simulate(contact, history, rtol=fr.DEFAULT_RTOL)
    return mesh.dissipation.values[-1] / exact - 1


def cycles(contact, A, moving):
    """Loading to ``(0.3 f P, 0.2 f p0)``, then two cycles of amplitude `A` of `moving` (``"Q"``: of
    ``A f P``, sigma held; ``"sigma"``: of ``A f p0``, Q held), 8 steps a segment."""
    Q0, sigma0 = 0.3 * contact.f * contact.P, 0.2 * contact.f * contact.p0
    swing = np.array([1, -1, 1, -1, 1]) * A
    Q = [0, Q0, *(Q0 + swing * contact.f * contact.P if moving == "Q" else [Q0] * 5)]
    sigma = [0, sigma0, *(sigma0 + swing * contact.f * contact.p0 if moving == "sigma" else [sigma0] * 5)]
    return fr.History.piecewise_linear(Q, sigma, 8)


def second_cycle(contact, A, moving, rtol=fr.DEFAULT_RTOL):
    """Energy [J/m] of the second of the two cycles of `cycles`, on the mesh adapted to `rtol`, and
    whether the model said that some increments fall below the solver's floor."""
    history = cycles(contact, A, moving)
    result = fr.simulate(contact, history, rtol=rtol)
    said = "solver's rounding allowance" in result.attrs.get("model_fallback", "")
    return result.dissipation.values[history.vertex_step[4] + 1 :].sum(), said


#: The rtol of the finer runs the defaults are compared with.
FINE_RTOL = 2e-5
#: The rtol of the ellipse's runs: the default's, then finer.
ELLIPSE_RTOLS = (fr.DEFAULT_RTOL, 5e-5, 2e-5, 1e-5)


def ellipse_cycle(contact, A, rtol):
    """Energy [J/m] of the last of two elliptical cycles of ``A f P`` and ``A f p0``, 90 degrees apart,
    about ``(0.3 f P, 0.2 f p0)``, 16 steps a cycle, on the mesh adapted to `rtol`; its nodes."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.sinusoidal(A * fP, A * fp0, 90, 2, 16, Q_mean=0.3 * fP, sigma_mean=0.2 * fp0)
    result = fr.simulate(contact, history, rtol=rtol)
    return result.dissipation.values[history.vertex_step[-2] + 1 :].sum(), result.sizes["x"]


def main():
    warnings.simplefilter("ignore", fr.ModelFallbackWarning)
    contact = hertz()
    print("A     | reversal W/W_exact-1 | Q cycles W/A^3 [J/m]: default, fine, diff. | sigma cycles W/A: same")
    print("(* the default's dataset says some increments fall below the solver's floor)")
    for A in AMPLITUDES:
        row = [f"{A:5.0e} | {reversal(contact, A):+10.2e}          "]
        for moving, power in (("Q", 3), ("sigma", 1)):
            default, said = second_cycle(contact, A, moving)
            fine, _ = second_cycle(contact, A, moving, FINE_RTOL)
            default, fine = default / A**power, fine / A**power
            mark = "*" if said else " "
            row.append(f"{default:.5e}{mark} {fine:.5e}, {default / fine - 1 if fine else float('nan'):+.1e}")
        print(" | ".join(row), flush=True)
    print("\nellipse of 1e-4 f P and 1e-4 f p0, last cycle: rtol | nodes | CPU s | W [J/m] | W / W(rtol=1e-5) - 1")
    rows = []
    for rtol in ELLIPSE_RTOLS:
        began = time.process_time()
        W, nodes = ellipse_cycle(contact, 1e-4, rtol)
        rows.append((rtol, nodes, time.process_time() - began, W))
    for rtol, nodes, seconds, W in rows:
        print(f"{rtol:5.0e} | {nodes:5d} | {seconds:6.1f} | {W:.7e} | {W / rows[-1][3] - 1:+.1e}")


if __name__ == "__main__":
    main()
