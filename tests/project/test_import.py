"""`import spectrocolor` stays light: no plotting, imaging, web or dask imports.

(The import time itself is measured by bench/bench_import.py; tests never assert timings.)
"""

import subprocess
import sys

HEAVY = ("matplotlib", "PIL", "fastapi", "uvicorn", "dask", "xarray", "tifffile", "colour", "h5py", "scipy")


def test_import_and_core_use_load_no_heavy_modules():
    code = (
        "import sys; import spectrocolor as sc; "
        "sc.tristimulus; sc.xy; sc.dominant_wavelength; sc.render; sc.Spectrum; "
        "print(','.join(sorted({m.split('.')[0] for m in sys.modules})))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    loaded = set(out.strip().split(","))
    assert "numpy" in loaded
    assert not loaded.intersection(HEAVY), loaded.intersection(HEAVY)
