"""Cold `import spectrocolor` time (best of 5 fresh interpreters). Goal: under 0.3 s.

Run: .venv/bin/python bench/bench_import.py
"""

import subprocess
import sys


def main() -> None:
    code = "import time; t = time.perf_counter(); import spectrocolor; print(time.perf_counter() - t)"
    used = (
        "import time; t = time.perf_counter(); import spectrocolor as sc; sc.tristimulus; sc.xy; "
        "sc.dominant_wavelength; sc.render; print(time.perf_counter() - t)"
    )
    base = "import time; t = time.perf_counter(); import numpy; print(time.perf_counter() - t)"
    ours = min(float(subprocess.check_output([sys.executable, "-c", code])) for _ in range(5))
    numpy_only = min(float(subprocess.check_output([sys.executable, "-c", base])) for _ in range(5))
    core = min(float(subprocess.check_output([sys.executable, "-c", used])) for _ in range(5))
    print(f"import spectrocolor            : {ours * 1e3:6.1f} ms (public names load lazily)")
    print(f"  + tristimulus, xy, dominant_wavelength, render: {core * 1e3:6.1f} ms (goal < 300 ms)")
    print(f"numpy alone                    : {numpy_only * 1e3:6.1f} ms")


if __name__ == "__main__":
    main()
