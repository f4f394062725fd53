# spectrocolor: two commands from a fresh clone.
#   make run          starts the SPECTRA explorer (the main job); PORT=8766 (0: any free port),
#                     HOST=... (another machine's reach needs ALLOW_REMOTE=1 too);
#                     CLASSROOM=1 opens a class on the local network (docs/classroom.md)
#   make test         builds its own virtual environment from the committed lock and runs every test
# More:
#   make docs         builds the API reference and guides offline (warnings are errors)
#   make lock         regenerates constraints.txt from the newest versions the registry serves
#   make test-latest  runs every test against the newest versions, in .venv-latest
#   make test-portable runs the numerical tests again under other BLAS kernels and SIMD choices
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
# `make run` installs what the explorer needs, `make test` everything, both into $(VENV) at the
# versions of constraints.txt. Each install leaves a stamp; everything's stamp ($(STAMP)) implies
# the explorer's, so either target works first from a fresh clone and neither installs twice.
APP_EXTRAS := app,fast
EXTRAS     := all,test,docs
APP_STAMP  := $(VENV)/.installed-app
STAMP      := $(VENV)/.installed-all
PIP        := $(BIN)/pip --disable-pip-version-check
PORT  ?= 8765
HOST  ?= $(if $(filter 1 yes true,$(CLASSROOM)),,127.0.0.1)
ALLOW_REMOTE ?=
CLASSROOM ?=

.PHONY: run test test-portable lint docs lock test-latest bench clean

$(BIN)/python:
	@echo "spectrocolor: creating the environment $(VENV) ($(PYTHON) -m venv)"
	@$(PYTHON) -m venv $(VENV)
	@$(PIP) install --quiet --upgrade pip

$(APP_STAMP): pyproject.toml constraints.txt | $(BIN)/python
	@echo "spectrocolor: installing the explorer (extras $(APP_EXTRAS): FastAPI, uvicorn, Pillow, numba) into $(VENV), a few minutes the first time"
	@$(PIP) install --quiet -c constraints.txt -e ".[$(APP_EXTRAS)]"
	@touch $@

$(STAMP): pyproject.toml constraints.txt | $(BIN)/python
	@echo "spectrocolor: installing everything (extras $(EXTRAS): the explorer, plots, images, tests, docs) into $(VENV), several minutes the first time"
	@$(PIP) install --quiet -c constraints.txt -e ".[$(EXTRAS)]"
	@touch $@ $(APP_STAMP)

# The former name of everything's stamp, for scripts that still ask for it.
$(VENV)/.installed: $(STAMP)
	@touch $@

# The explorer prints the rest: serving at its URL, compiling the kernels in the background
# (results use the NumPy path until they are ready, and say so), and when they are ready.
run: $(APP_STAMP)
	@SPECTROCOLOR_MAKE_RUN=1 $(BIN)/spectrocolor app --port $(PORT) $(if $(HOST),--host $(HOST)) $(if $(filter 1 yes true,$(ALLOW_REMOTE)),--allow-remote) $(if $(filter 1 yes true,$(CLASSROOM)),--classroom)

test: $(STAMP)
	$(BIN)/ruff check src tests bench docs tools
	$(BIN)/mypy src
	$(BIN)/python -m spectrocolor.recovery.warmup
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

# Two complete passes of the table's bench scripts into bench/results.json, then the README's
# speed table generated from it (figures the two passes do not reproduce within 30 % say so).
bench: $(STAMP)
	$(BIN)/python bench/run_all.py --output bench/results.json --passes 2
	$(BIN)/python tools/speed_table.py --results bench/results.json --readme README.md

clean:
	rm -rf $(VENV) .venv-latest .venv-lock .pytest_cache .hypothesis artifacts docs/api/_build docs/api/reference docs/api/guides
