# spectrocolor: two commands from a fresh clone.
#   make run          starts the SPECTRA explorer (the main job)
#   make test         builds its own virtual environment from the committed lock and runs every test
# More:
#   make docs         builds the API reference and guides offline (warnings are errors)
#   make lock         regenerates constraints.txt from the newest versions the registry serves
#   make test-latest  runs every test against the newest versions, in .venv-latest
#   make test-portable runs the numerical tests again under other BLAS kernels and SIMD choices
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
EXTRAS := all,test,docs

.PHONY: run test test-portable lint docs lock test-latest bench clean

$(STAMP): pyproject.toml constraints.txt
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -c constraints.txt -e ".[$(EXTRAS)]"
	$(BIN)/python -m spectrocolor.recovery.compiled
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/spectrocolor app

test: $(STAMP)
	$(BIN)/ruff check src tests bench docs tools
	$(BIN)/python -m spectrocolor.recovery.compiled
	$(BIN)/python -m pytest -q --doctest-modules src tests
	$(MAKE) --no-print-directory docs

# The numerical tests again under OpenBLAS's Prescott and Haswell kernels and NumPy's baseline
# loops, one BLAS thread each (tools/portable_tests.py says what is left out and why). Run it
# before stopping: a float compared bit for bit fails here, not on the next user's CPU.
test-portable: $(STAMP)
	$(BIN)/python tools/portable_tests.py --python $(BIN)/python

docs: $(STAMP)
	$(BIN)/sphinx-build -q -W --keep-going -b html docs/api docs/api/_build/html
	@echo "API reference and guides: docs/api/_build/html/index.html"

lock:
	rm -rf .venv-lock
	$(PYTHON) -m venv .venv-lock
	.venv-lock/bin/pip install --quiet --upgrade pip
	.venv-lock/bin/pip install --quiet -e ".[$(EXTRAS)]"
	( echo "# Exact versions that 'make test' installs (pip constraints). Regenerate with 'make lock'."; \
	  .venv-lock/bin/pip freeze --exclude-editable | LC_ALL=C sort ) > constraints.txt
	rm -rf .venv-lock

test-latest:
	rm -rf .venv-latest
	$(PYTHON) -m venv .venv-latest
	.venv-latest/bin/pip install --quiet --upgrade pip
	.venv-latest/bin/pip install --quiet --upgrade -e ".[$(EXTRAS)]"
	.venv-latest/bin/python -m pytest -q --doctest-modules src tests

bench: $(STAMP)
	for f in bench/bench_*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) .venv-latest .venv-lock .pytest_cache .hypothesis artifacts docs/api/_build docs/api/reference docs/api/guides
