"""The stick zone of a rounded flat close to sliding, against Ciavarella-Jaeger.

Shear to ``Q = psi f P`` in 8 proportional steps on the rounded flat of tests/test_hard_cases.py
(flat half-width b = 1 mm, corners of radius 20 mm, E* = 115 GPa, f = 0.5, P = 3e5 N/m). The
stick zone ``[-c, c]`` tends to the flat, ``c - b`` shrinking like ``(fP - Q)^(2/3)``. For each
``psi`` and model (the default: the exact model of Q alone, fretting.models.exact; method 4 on the
mesh of rtol 1e-4 and on grids) this prints the nodes, ``c - b`` of the engine (half its zone's width, minus
b) and of Ciavarella-Jaeger, the relative error, and whether the zone covers the flat. Then
what decides stick in the strip ``[b, c]``: the slip ``f h0(c)`` [m] there, against how far from
flat over the flat each discretisation's slip under ``q = f p`` everywhere is (its range there).

Run:  python benchmarks/rounded_flat_near_sliding.py   (about 3 seconds)
"""

import numpy as np

import fretting as fr
from fretting.physics import closed_forms

CONTACT = fr.Contact(fr.RoundedFlat(b=1e-3, R=0.02), 115e9, 0.5, 3e5)
MODELS = {"default": {}, "rtol 1e-4": {"rtol": 1e-4}, "grid 384": {"nodes": 384}, "grid 1536": {"nodes": 1536}}


def main():
    b, fP = CONTACT.profile.b, CONTACT.f * CONTACT.P
    print("psi       model       nodes   c - b [m]   exact [m]   error    covers the flat")
    for psi in (0.999, 0.9999, 0.99999, 0.999999):
        exact = closed_forms.ciavarella_jaeger(CONTACT, psi * fP, np.zeros(1))[1].a - b
        history = fr.History.piecewise_linear([0.0, psi * fP], [0.0, 0.0], 8)
        for label, model in MODELS.items():
            result = fr.simulate(CONTACT, history, **model).isel(step=-1)
            start, end = result.stick_start.values[0], result.stick_end.values[0]
            strip = (end - start) / 2 - b
            covers = start < -b and end > b
            print(
                f"{psi:<9} {label:<11} {result.attrs['nodes']:5d}   {strip:+.3e}  {exact:.3e}   "
                f"{strip / exact - 1:+.3f}   {'yes' if covers else 'no'}"
            )
    strip_slips()


def sliding_unevenness(scene):
    """Range [m] over the flat of the slip under ``q = f p`` at every node (``Q = f P``, rigid shift free)."""
    contact = scene.contact
    g_stuck = scene.g_stuck(contact.f * contact.P, 0.0)
    slip = np.linalg.lstsq(scene.G, g_stuck - scene.limit, rcond=None)[0]
    return np.ptp(slip[np.abs(scene.x) <= contact.profile.b])


def strip_slips():
    b, fP, R = CONTACT.profile.b, CONTACT.f * CONTACT.P, CONTACT.profile.R
    for psi in (0.999, 0.99999, 0.999999):
        strip = closed_forms.ciavarella_jaeger(CONTACT, psi * fP, np.zeros(1))[1].a - b
        print(f"f h0(c) at psi = {psi}: {CONTACT.f * strip**2 / (2 * R):.2g} m")
    history = fr.History.piecewise_linear([0.0, 0.999999 * fP], [0.0, 0.0], 8)
    mesh = fr.models.Mesh(theta=fr.adapted_mesh(CONTACT, history, 1e-4)).build(CONTACT)
    for label, scene in (("grid 384", fr.models.Grid(384).build(CONTACT)), (f"mesh of {mesh.x.size} nodes", mesh)):
        print(f"slip under q = f p, range over the flat, {label}: {sliding_unevenness(scene):.2g} m")


if __name__ == "__main__":
    main()
