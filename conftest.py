"""Root test configuration, shared by the doctests in src/ and the tests in tests/."""

import numpy as np
import pytest


@pytest.fixture(autouse=True)
def _numpy_default_printing():
    """colour-science (test-only) switches NumPy to its 1.13 printing when imported; examples
    in our docstrings show NumPy's default printing, so each test runs with the default."""
    with np.printoptions(legacy=False):
        yield
