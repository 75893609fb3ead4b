# The book's two commands: `make book` builds the HTML book, `make test` runs every test.
# Each creates .venv from environment.txt when it is missing or older than its pins.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# Notebooks must keep Jupyter's inline backend (Agg would drop every figure): unset it for them.
export PYDEVD_DISABLE_FILE_VALIDATION := 1
NB_ENV := env -u MPLBACKEND

.PHONY: book test unit notebooks notebooks-other-machine html-check bench execute clean

$(STAMP): environment.txt pkg/pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(BIN)/python -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

book: $(STAMP)
	$(NB_ENV) $(BIN)/jupyter-book build . -W -n --keep-going

unit: $(STAMP)
	MPLBACKEND=Agg $(BIN)/pytest --doctest-modules pkg/mechnum tests

notebooks: $(STAMP)
	$(NB_ENV) $(BIN)/pytest --nbval --nbval-sanitize-with book/nbval_sanitize.cfg book

# The same, with the arithmetic of another machine: OpenBLAS's oldest x86-64 kernels (Prescott)
# and numpy's SIMD loops reduced to the x86-64-v2 baseline. A printed digit that changes here is
# round-off, and must be printed as a checked bound instead (CONTRIBUTING.md).
OTHER_MACHINE := OPENBLAS_CORETYPE=Prescott NPY_DISABLE_CPU_FEATURES=X86_V3,X86_V4,AVX512_ICL,AVX512_SPR
notebooks-other-machine: $(STAMP)
	$(NB_ENV) $(OTHER_MACHINE) $(BIN)/pytest --nbval --nbval-sanitize-with book/nbval_sanitize.cfg \
		-p no:cacheprovider book

html-check: $(STAMP)
	MECHNUM_BUILT_HTML=_build/html $(BIN)/pytest tests/test_built_html.py

test: unit notebooks notebooks-other-machine book html-check

bench: $(STAMP)
	MPLBACKEND=Agg $(BIN)/pytest bench -o python_files='bench_*.py' --benchmark-only \
		--benchmark-columns=min,median,max,rounds

# Re-execute chapters in place after editing them (all of them, or NB=book/<chapter>.ipynb),
# without the execution timings that would dirty the diff.
NB ?= $(wildcard book/*.ipynb)
execute: $(STAMP)
	$(NB_ENV) $(BIN)/python .ci/execute_notebooks.py $(NB)

clean:
	rm -rf _build .pytest_cache .hypothesis .benchmarks
