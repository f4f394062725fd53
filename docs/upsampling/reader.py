"""Reference reader for spectrocolor spectral upsampling tables (.scup, format version 1)
and texel coefficient files (.sctx, format version 1).

Standalone (Python 3 and NumPy only); the layouts and the lookup are documented in
``docs/upsampling.md``. Usage::

    python reader.py TABLE.scup R G B               # prints "wavelength_nm reflectance" lines
    python reader.py TABLE.scup TEXELS.sctx X Y     # the same for texel (column X, row Y)
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


def read_texels(path):
    """Return (node indices (H, W, 4) uint32, weights (H, W, 4) float32) of a .sctx file."""
    with open(path, "rb") as handle:
        magic, version, width, height, n, K, fingerprint = struct.unpack("<8sIIIIII", handle.read(32))
        if magic != b"SCTEXEL\0" or version != 1:
            raise ValueError(f"{path}: not a version-1 texel coefficient file")
        nodes = np.fromfile(handle, dtype="<u4", count=height * width * 4)
        weights = np.fromfile(handle, dtype="<f4", count=height * width * 4)
    if weights.size != height * width * 4:
        raise ValueError(f"{path}: truncated")
    return nodes.reshape(height, width, 4), weights.reshape(height, width, 4)


def texel_spectrum(rho, nodes, weights):
    """One texel's reflectance: its four node spectra blended with its (float32) weights."""
    flat = rho.reshape(-1, rho.shape[-1])
    value = flat[nodes[0]] * float(weights[0])
    for j in range(1, 4):
        value = value + flat[nodes[j]] * float(weights[j])
    return np.minimum(value, 1.0)


if __name__ == "__main__":
    wavelengths, nodes = read_table(sys.argv[1])
    if sys.argv[2].endswith(".sctx"):
        texel_nodes, texel_weights = read_texels(sys.argv[2])
        x, y = int(sys.argv[3]), int(sys.argv[4])
        values = texel_spectrum(nodes, texel_nodes[y, x], texel_weights[y, x])
    else:
        values = spectrum(nodes, [float(v) for v in sys.argv[2:5]])
    for wavelength, value in zip(wavelengths, values, strict=True):
        print(f"{wavelength:.17g} {value:.17g}")
