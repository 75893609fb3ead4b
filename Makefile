# The book's two commands: `make book` builds the HTML book, `make test` runs every test.
# Each creates .venv from environment.txt when it is missing or older than its pins.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# Notebooks must keep Jupyter's inline backend (Agg would drop every figure): unset it for them.
export PYDEVD_DISABLE_FILE_VALIDATION := 1
NB_ENV := env -u MPLBACKEND

.PHONY: book test unit notebooks html-check bench clean

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

html-check: $(STAMP)
	MECHNUM_BUILT_HTML=_build/html $(BIN)/pytest tests/test_built_html.py

test: unit notebooks book html-check

bench: $(STAMP)
	MPLBACKEND=Agg $(BIN)/pytest bench -o python_files='bench_*.py' --benchmark-only \
		--benchmark-columns=min,median,max,rounds

clean:
	rm -rf _build .pytest_cache .hypothesis .benchmarks
