"""Seed 002's Figs. 9 and 10 drawn from the library: ``.venv/bin/python tools/draw_step4.py``.

Fig. 9: the emission spectra of SPECTRA's monitor's phosphors (``display_emission``) with the
brightness sensitivity curve ȳ; Fig. 10: its excitation function γ (64 levels, γ = 2.204).
Writes ``docs/images/spectra_step4.png``.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import spectrocolor as sc  # noqa: E402

grid = sc.wavelength_grid(400, 700, 1)
primaries = sc.primary_emission("SPECTRA 7000K", grid)
codes, gamma = sc.excitation_function("SPECTRA 7000K")
ybar = sc.observer("1931").resample(grid).values[1]

fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.6), gridspec_kw={"width_ratios": [1.6, 1]})
for values, colour, name in zip(primaries.values, ("#c0392b", "#27ae60", "#2e6fd8"),
                                ("red", "green", "blue"), strict=True):
    a.plot(grid, values / primaries.values.max(), color=colour, label=f"{name} phosphor")
a.plot(grid, ybar, "k--", label="ȳ (brightness sensitivity)")
a.set(xlabel="wavelength (nm)", ylabel="relative radiance", xlim=(400, 700),
      title="Fig. 9: emission of SPECTRA's monitor")
a.legend(fontsize=8)
b.plot(codes, gamma, "k.-", markersize=3)
b.axhline(0.5, color="0.7", lw=0.8)
b.axvline(46, color="0.7", lw=0.8)
b.set(xlabel="code (0-63)", ylabel="fraction of full emission",
      title="Fig. 10: excitation function γ")
fig.tight_layout()
fig.savefig("docs/images/spectra_step4.png", dpi=110)
print("wrote docs/images/spectra_step4.png", np.round(gamma[46], 3))
