"""Van Trigt's structure (seed 004, Figs. 3–10) drawn from the library.

``.venv/bin/python tools/draw_van_trigt.py`` writes, on 360–830 nm at 1 nm (the CIE tables' full
range and native step, on which the library reproduces the line equations of his Fig. 7
caption):

* ``docs/images/reflectance_classes.png`` — Figs. 7–8: the domain of validity under A and D65
  with the regions of classes 1 and 2, their end points and the CIE 13.3 test colour samples
  (numbered; 9 and 12 fall outside under D65);
* ``docs/images/reflectance_validity.png`` — Figs. 11–12: the maximum luminance factor;
* ``docs/images/reflectance_y_lambda1.png`` — Figs. 9–10: Y(λ₁) and Y_M(λ₁) of both classes;
* ``docs/images/reflectance_generating.png`` — Figs. 5–6: ρ(λ; λ₁) of class 2 and of class 1
  (zero at 360 nm) for λ₁ = 500 and 564 nm under D65;
* ``docs/images/reflectance_boundary_locus.png`` — Figs. 3–4 with the classes' chromaticities.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import spectrocolor as sc  # noqa: E402
from spectrocolor.lighting.spectra import tcs_reflectances  # noqa: E402
from spectrocolor.recovery import plots  # noqa: E402
from spectrocolor.recovery.validity import (  # noqa: E402
    boundary_locus,
    domain_of_validity,
    generating_functions,
)

GRID = (360.0, 830.0, 1.0)
OUT = "docs/images/"
grid_nm = sc.wavelength_grid(*GRID)


def tcs_xy(illuminant):
    XYZ = tcs_reflectances(grid_nm) @ np.asarray(sc.weights(grid_nm, observer="1931", illuminant=illuminant))
    return {str(i + 1): xy for i, xy in enumerate(XYZ[:, :2] / XYZ.sum(axis=1, keepdims=True))}


def pair(name, draw, size=(13, 6.2)):
    fig, axes = plt.subplots(1, 2, figsize=size)
    for ax, (illuminant, fig_no) in zip(axes, (("A", 7), ("D65", 8)), strict=True):
        draw(ax, illuminant, fig_no)
    fig.tight_layout()
    fig.savefig(OUT + name, dpi=90)
    plt.close(fig)
    print("wrote", OUT + name)


domains = {ill: domain_of_validity(ill, wavelengths=GRID) for ill in ("A", "D65")}
generating = {ill: generating_functions(ill, wavelengths=GRID) for ill in ("A", "D65")}

pair("reflectance_classes.png", lambda ax, ill, n: plots.domain_of_validity_plot(
    domains[ill], ax=ax, luminance=False, points=tcs_xy(ill), points_label="CIE 13.3 test colours",
    title=f"Classes, {ill}, 360–830 nm, 1 nm (van Trigt Fig. {n})"))
pair("reflectance_validity.png", lambda ax, ill, n: plots.domain_of_validity_plot(
    domains[ill], ax=ax, classes=False,
    title=f"Max. Y/Y0 with ρ ≤ 1, {ill}, 360–830 nm (van Trigt Fig. {n + 4})"), size=(13, 6.0))
pair("reflectance_y_lambda1.png", lambda ax, ill, n: plots.generating_luminance_plot(
    generating[ill], ax=ax,
    title=f"Y(λ₁) and Y_M(λ₁), illuminant {ill} (van Trigt Fig. {n + 2})"), size=(13, 4.6))
pair("reflectance_boundary_locus.png", lambda ax, ill, n: plots.boundary_locus_plot(
    boundary_locus(ill, wavelengths=GRID), generating[ill], ax=ax,
    title=f"Boundary locus, {ill}, 360–830 nm, 1 nm (Fig. {n - 4})"))

g = generating["D65"]
fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), sharey=True)
for ax, (cls, end, fig_no) in zip(axes, (("2", None, 5), ("1", 360.0, 6)), strict=True):
    rows = g.family(cls, end)
    picked = [rows[np.argmin(np.abs(g.lambda1_nm[rows] - lam))] for lam in (500.0, 564.0)]
    spectrum = sc.Spectrum(g.wavelengths_nm, g.reflectance[picked])
    labels = [f"λ₁ = {g.lambda1_nm[i]:g} nm, xy = ({g.xy[i, 0]:.4f}, {g.xy[i, 1]:.4f})" for i in picked]
    plots.reflectance_curves(spectrum, ax=ax, labels=labels,
                             title=f"Class {cls} (van Trigt Fig. {fig_no}), D65, 1 nm")
fig.tight_layout()
fig.savefig(OUT + "reflectance_generating.png", dpi=90)
plt.close(fig)
print("wrote", OUT + "reflectance_generating.png")
