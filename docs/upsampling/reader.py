"""Reference reader for spectrocolor spectral upsampling tables (.scup, format version 1).

Standalone (Python 3 and NumPy only); the layout and the lookup are documented in
``docs/upsampling.md``. Usage::

    python reader.py TABLE.scup R G B      # prints "wavelength_nm reflectance" lines
"""

import struct
import sys

import numpy as np


def read_table(path):
    """Return (wavelengths_nm (K,), node reflectances (n, n, n, K)) of a .scup file."""
    with open(path, "rb") as handle:
        head = handle.read(112)
        magic, version, n, K, J, start, step = struct.unpack("<8sIIII2d", head[:40])
        if magic != b"SCUPTBL\0" or version != 1:
            raise ValueError(f"{path}: not a version-1 upsampling table")
        handle.seek(112 + J)
        rho = np.fromfile(handle, dtype="<f8", count=n * n * n * K)
    if rho.size != n * n * n * K:
        raise ValueError(f"{path}: truncated")
    return start + step * np.arange(K), rho.reshape(n, n, n, K)


def spectrum(rho, rgb):
    """Tetrahedral blend of the node spectra for one colour ``rgb`` in [0, 1]^3."""
    n = rho.shape[0]
    s = np.asarray(rgb, dtype=float) * (n - 1)
    base = np.minimum(s.astype(int), n - 2)
    frac = s - base
    order = sorted(range(3), key=lambda axis: -frac[axis])  # stable: ties keep axis order
    f = frac[order]
    weights = (1.0 - f[0], f[0] - f[1], f[1] - f[2], f[2])
    corner = base.copy()
    value = rho[tuple(corner)] * weights[0]
    for j, axis in enumerate(order):
        corner[axis] += 1
        value = value + rho[tuple(corner)] * weights[j + 1]
    return np.minimum(value, 1.0)


if __name__ == "__main__":
    wavelengths, nodes = read_table(sys.argv[1])
    values = spectrum(nodes, [float(v) for v in sys.argv[2:5]])
    for wavelength, value in zip(wavelengths, values, strict=True):
        print(f"{wavelength:.17g} {value:.17g}")
