"""Former home of the spectral-file readers and writers; they live in :mod:`spectrocolor.io`.

Kept so that ``from spectrocolor.spectrum_io import read_spectra`` keeps working.
"""

from .io import read_spectra, spectra_to_csv, write_spectra

__all__ = ["read_spectra", "spectra_to_csv", "write_spectra"]
