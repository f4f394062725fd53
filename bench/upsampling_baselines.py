"""Baselines for the spectral-upsampling comparison (bench and docs only; never imported by the
package). Each takes linear RGB (N, 3) of a space and returns reflectances (N, K) on ``grid``.

* :func:`smits` — Smits (1999): white plus two of cyan/magenta/yellow/red/green/blue, chosen by
  the order of the channels (the published construction; its ten-bin basis spectra are the
  paper's table, taken from colour-science's copy ``colour.recovery.SDS_SMITS1999``).
* :class:`SigmoidPolynomial` — the model of Jakob & Hanika (2019): ``ρ(λ) = S(c0 x² + c1 x + c2)``
  with ``S(z) = 1/2 + z / (2 sqrt(1 + z²))`` and ``x`` the wavelength scaled to [0, 1]; the three
  coefficients of each colour are fitted here by a damped Gauss-Newton iteration on the CIELAB
  difference (as in the paper), continued from grey toward the target. ``fit`` gives the
  model's per-colour optimum; ``table``/``from_table`` a coefficient grid with trilinear
  interpolation (our own grid: n³ nodes in linear RGB, not the paper's 64³ scaled grid).
* :func:`meng` — Meng et al. (2015) via colour-science's ``XYZ_to_sd_Meng2015`` (slow: a few
  colours only).

References
----------
B. Smits, "An RGB-to-spectrum conversion for reflectances", J. Graphics Tools 4(4), 11–22 (1999).
W. Jakob, J. Hanika, "A low-dimensional function space for efficient spectral upsampling",
Computer Graphics Forum 38(2), 147–155 (2019).
J. Meng, F. Simon, J. Hanika, C. Dachsbacher, "Physically meaningful rendering using tristimulus
colours", Computer Graphics Forum 34(4), 31–40 (2015).
"""

from __future__ import annotations

import numpy as np

import spectrocolor as sc


def _smits_basis(grid: np.ndarray) -> dict[str, np.ndarray]:
    import colour

    out = {}
    for name, sd in colour.recovery.SDS_SMITS1999.items():
        out[name] = np.interp(grid, sd.wavelengths, sd.values)  # held flat beyond 380–720 nm
    return out


def smits(rgb_linear: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Smits (1999) for linear RGB (N, 3) on ``grid``."""
    b = _smits_basis(grid)
    r, g, bl = (rgb_linear[:, i:i + 1] for i in range(3))
    red_min = (r <= g) & (r <= bl)
    green_min = ~red_min & (g <= bl)
    out = np.where(
        red_min,
        r * b["white"] + np.where(g <= bl, (g - r) * b["cyan"] + (bl - g) * b["blue"],
                                  (bl - r) * b["cyan"] + (g - bl) * b["green"]),
        np.where(
            green_min,
            g * b["white"] + np.where(r <= bl, (r - g) * b["magenta"] + (bl - r) * b["blue"],
                                      (bl - g) * b["magenta"] + (r - bl) * b["red"]),
            bl * b["white"] + np.where(r <= g, (r - bl) * b["yellow"] + (g - r) * b["green"],
                                       (g - bl) * b["yellow"] + (r - g) * b["red"]),
        ),
    )
    return out


def _sigmoid(z):
    return 0.5 + z / (2.0 * np.sqrt(1.0 + z * z))


class SigmoidPolynomial:
    """Jakob & Hanika's sigmoid-polynomial model, fitted in CIELAB under one illuminant."""

    def __init__(self, W: np.ndarray, grid: np.ndarray, matrix: np.ndarray):
        self.W = W
        self.white = W.sum(axis=0)
        self.matrix = matrix  # XYZ100 = matrix @ rgb_linear
        x = (grid - grid[0]) / (grid[-1] - grid[0])
        self.basis = np.stack([x * x, x, np.ones_like(x)])  # (3, K)

    def spectra(self, coefficients: np.ndarray) -> np.ndarray:
        return _sigmoid(coefficients @ self.basis)

    def _lab(self, coefficients):
        return sc.lab(self.spectra(coefficients) @ self.W, self.white)


    def fit(self, rgb_linear: np.ndarray, steps: int = 8) -> np.ndarray:
        """Coefficients (N, 3) reproducing each colour as closely as the model can.

        Per colour, Levenberg-Marquardt (SciPy) on the CIELAB difference (the paper's
        objective), continued from grey toward the target in ``steps`` stages, each started
        from the previous stage's coefficients.
        """
        from scipy.optimize import least_squares

        out = np.zeros((len(rgb_linear), 3))
        for index, rgb in enumerate(rgb_linear):
            c = np.zeros(3)
            for k in range(1, steps + 1):
                target = sc.lab((0.5 + k / steps * (rgb - 0.5)) @ self.matrix.T, self.white)
                c = least_squares(lambda q, target=target: self._lab(q) - target, c,
                                  method="lm").x
            out[index] = c
        return out

    def table(self, n: int) -> np.ndarray:
        """Fitted coefficients at the n³ nodes of the linear-RGB cube, (n, n, n, 3)."""
        axis = np.linspace(0.0, 1.0, n)
        nodes = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), -1).reshape(-1, 3)
        return self.fit(nodes, steps=4).reshape(n, n, n, 3)

    @staticmethod
    def from_table(table: np.ndarray, rgb_linear: np.ndarray) -> np.ndarray:
        """Trilinear interpolation of the coefficient table at ``rgb_linear`` (in [0, 1])."""
        n = table.shape[0]
        s = np.clip(rgb_linear, 0.0, 1.0) * (n - 1)
        i = np.minimum(s.astype(int), n - 2)
        f = s - i
        out = np.zeros((len(rgb_linear), 3))
        for corner in np.ndindex(2, 2, 2):
            w = np.prod(np.where(np.array(corner), f, 1.0 - f), axis=-1)
            out += w[:, None] * table[i[:, 0] + corner[0], i[:, 1] + corner[1],
                                      i[:, 2] + corner[2]]
        return out


def meng(XYZ100: np.ndarray, grid: np.ndarray, illuminant: str = "D65") -> np.ndarray:
    """Meng et al. (2015) by colour-science, one colour at a time (slow)."""
    import colour

    shape = colour.SpectralShape(grid[0], grid[-1], grid[1] - grid[0])
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    light = colour.SDS_ILLUMINANTS[illuminant].copy().align(shape)
    out = []
    for XYZ in XYZ100:
        try:
            sd = colour.recovery.XYZ_to_sd_Meng2015(XYZ / 100.0, cmfs, light)
            out.append(np.interp(grid, sd.wavelengths, sd.values))
        except Exception:  # its optimiser fails outside the solid
            out.append(np.full(grid.size, np.nan))
    return np.array(out)
