# The book's two commands: `make book` builds the HTML book, `make test` runs every test.
# Each creates .venv from environment.txt when it is missing or older than its pins.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# Notebooks must keep Jupyter's inline backend (Agg would drop every figure): unset it for them.
export PYDEVD_DISABLE_FILE_VALIDATION := 1
NB_ENV := env -u MPLBACKEND

.PHONY: book book-committed book-student student-src downloads grade nbgrader pdf \
	pdf-answer-key pdf-student test unit lint explore notebooks notebooks-other-machine html-check \
	bench execute lab clean certify mutate mutate-check

$(STAMP): environment.txt pkg/pyproject.toml course/pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(BIN)/python -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

# reveal.js for the lectures' slides (book/_ext/slides.py), from the npm registry at the version
# book/_ext/package-lock.json locks, installed into .venv/npm; the book's build copies what the
# decks use into _build/html/slides, so that they load nothing from the network.
NPM := $(VENV)/npm
REVEAL := $(NPM)/.installed
export MECHNUM_REVEALJS := $(CURDIR)/$(NPM)/node_modules/reveal.js
$(REVEAL): book/_ext/package.json book/_ext/package-lock.json $(STAMP)
	@command -v npm >/dev/null || { echo "the slides need npm (Debian: apt-get install npm)"; \
		exit 1; }
	rm -rf $(NPM) && mkdir -p $(NPM)
	cp book/_ext/package.json book/_ext/package-lock.json $(NPM)/
	npm ci --prefix $(NPM) --ignore-scripts --no-audit --no-fund --loglevel=error
	touch $(REVEAL)

book: downloads $(REVEAL)
	$(NB_ENV) $(BIN)/jupyter-book build . -W -n --keep-going

# The same book rendered from the outputs committed with the notebooks, executing nothing: what
# `make test` builds after strict nbval has executed every notebook and checked that its outputs
# are the committed ones. Its page "Execution statistics" shows strict nbval's measurements.
COMMITTED_CONFIG := _build/committed_config.yml
book-committed: downloads $(REVEAL)
	$(BIN)/python .ci/book_config.py $(COMMITTED_CONFIG) execute.execute_notebooks=off
	$(NB_ENV) $(BIN)/jupyter-book build . --config $(COMMITTED_CONFIG) -W -n --keep-going

# What the page "Run the chapters yourself" serves: the package's wheel, and the chapters with
# every file they read (the registry, the certificates) and cite (references.bib), as listed in
# .ci/chapters_zip.py.
DOWNLOADS := _build/downloads
downloads: $(STAMP)
	rm -rf $(DOWNLOADS) pkg/build
	$(BIN)/python -m pip wheel --quiet --disable-pip-version-check --no-deps \
		--wheel-dir $(DOWNLOADS) ./pkg
	rm -rf pkg/build
	$(BIN)/python .ci/chapters_zip.py book $(DOWNLOADS)/mechnum-chapters.zip

# The same book without the solutions of the exercises, for a class, in _build/student/_build/html.
# It is built from a copy of the sources without the solutions (mechnum_course.student), so
# that the pages, their .ipynb downloads and the served zip hold none; the copy renders the
# committed outputs (the tests have checked them) instead of executing again, except the
# exercises' check cells, whose output is recomputed for the unfilled starters ("not yet").
STUDENT := _build/student
STUDENT_SRC := $(STUDENT)/src
STUDENT_TITLE := title+= (student edition)
student-src: downloads
	rm -rf $(STUDENT_SRC) && mkdir -p $(STUDENT_SRC)/$(DOWNLOADS)
	cp -r _toc.yml CITATION.cff book $(STUDENT_SRC)/
	mkdir -p $(STUDENT_SRC)/course && cp course/rubric.md $(STUDENT_SRC)/course/
	$(BIN)/python -m mechnum_course.student $(STUDENT_SRC)/book
	$(BIN)/python .ci/book_config.py $(STUDENT_SRC)/_config.yml "$(STUDENT_TITLE)" \
		sphinx.config.hide_solutions=true execute.execute_notebooks=off \
		"sphinx.config.printed_edition=the students' edition, every exercise without its solution"
	cp $(DOWNLOADS)/*.whl $(STUDENT_SRC)/$(DOWNLOADS)/
	$(BIN)/python .ci/chapters_zip.py $(STUDENT_SRC)/book \
		$(STUDENT_SRC)/$(DOWNLOADS)/mechnum-chapters.zip

book-student: student-src $(REVEAL)
	$(NB_ENV) $(BIN)/jupyter-book build $(STUDENT_SRC) --path-output $(STUDENT) -W -n --keep-going

# Grade a folder of student notebooks: make grade SUBMISSIONS=folder [OUT=folder] (grades.csv,
# feedback/<student>.md and summary.txt, by default in SUBMISSIONS/grading). Each notebook runs
# confined, only to extract its functions; each function is graded from its source in a fresh
# confined process on the public and hidden cases (course/mechnum_course/grading, and the book's
# page "Grading the exercises", which also gives the command for a container with no network).
grade: $(STAMP)
	@test -n "$(SUBMISSIONS)" || { echo "usage: make grade SUBMISSIONS=<folder of notebooks>" \
		"[OUT=<folder>]"; exit 2; }
	$(NB_ENV) $(BIN)/python -m mechnum_course.grading $(SUBMISSIONS) $(if $(OUT),--out $(OUT))

# The self-checked exercises as an nbgrader course in _build/nbgrader (mechnum_course.nbgrader):
# source notebooks with solution regions and autograded tests that hold the hidden cases.
NBGRADER := _build/nbgrader
nbgrader: $(STAMP)
	rm -rf $(NBGRADER)
	$(BIN)/python -m mechnum_course.nbgrader $(NBGRADER)

# The property-based tests draw the same examples on every run (tests/conftest.py), also when
# pytest-xdist shares them out between the cores; `make explore` draws new ones, to search for
# counterexamples, and fails on numpy's overflow and invalid-value warnings too (not in `make
# test`: whether such a warning is raised can depend on the CPU's SIMD loops).
XDIST := -n auto --dist worksteal
unit: $(STAMP)
	HYPOTHESIS_PROFILE=repeatable MPLBACKEND=Agg $(BIN)/pytest $(XDIST) --doctest-modules \
		pkg/mechnum course/mechnum_course book/published.py tests

# The linter, ruff (configured in pkg/pyproject.toml), over the package, its tests and benchmarks.
lint: $(STAMP)
	$(BIN)/ruff check --config pkg/pyproject.toml pkg course tests bench book/published.py

explore: $(STAMP)
	HYPOTHESIS_PROFILE=explore MPLBACKEND=Agg $(BIN)/pytest $(XDIST) -W error::RuntimeWarning tests

# Strict nbval: every notebook executed in a fresh kernel, its outputs compared with the committed
# ones. Each run records how long each notebook took (book/_ext/execution_statistics.py) in
# _build/execution/, for the page "Execution statistics" and the lectures' budget.
EXECUTION := _build/execution
NBVAL := $(BIN)/pytest --nbval --nbval-sanitize-with book/nbval_sanitize.cfg
notebooks: $(STAMP)
	$(NB_ENV) MECHNUM_EXECUTION_RECORD=$(EXECUTION)/notebooks.json $(NBVAL) book

# The same, with the arithmetic of another machine: OpenBLAS's oldest x86-64 kernels (Prescott)
# and numpy's SIMD loops reduced to the x86-64-v2 baseline. A printed digit that changes here is
# round-off, and must be printed as a checked bound instead (CONTRIBUTING.md).
OTHER_MACHINE := OPENBLAS_CORETYPE=Prescott NPY_DISABLE_CPU_FEATURES=X86_V3,X86_V4,AVX512_ICL,AVX512_SPR
notebooks-other-machine: $(STAMP)
	$(NB_ENV) $(OTHER_MACHINE) MECHNUM_EXECUTION_RECORD=$(EXECUTION)/notebooks-other-machine.json \
		$(NBVAL) -p no:cacheprovider book

# The tests of the built books: offline pages, rendered TeX, the downloads run in a fresh
# environment (every notebook of both editions' zips, with the served wheel), the student
# edition hides every solution, every page and every slide of the lectures' decks in headless
# Chromium, and the layout at 1280 and 390 px (Debian's package chromium; without it those tests
# are skipped, and said so), and the lectures' execution times that strict nbval measured. Each test module runs whole in one of
# two processes (the browser tests visit each page once; the downloads test, the longest, runs
# beside them).
html-check: $(STAMP)
	@command -v chromium >/dev/null || echo "*** chromium is not installed: the browser tests" \
		"(tests/test_browser.py) are skipped; Debian: apt-get install chromium ***"
	MECHNUM_BUILT_HTML=_build/html MECHNUM_STUDENT_HTML=_build/student/_build/html \
		$(BIN)/pytest -n auto --dist loadfile -rsxX tests/test_built_html.py tests/test_downloads.py \
		tests/test_student_edition.py tests/test_browser.py tests/test_lecture_budget.py

# Every test, each step on both cores after the linter: the unit tests shared out by
# pytest-xdist; the two strict nbval runs side by side; the book (from the outputs strict nbval
# has just checked: executing the notebooks a third time would repeat that check) beside its
# student edition; their tests.
test: $(STAMP)
	$(MAKE) lint
	$(MAKE) unit
	$(MAKE) -j2 --output-sync=target notebooks notebooks-other-machine
	$(MAKE) -j2 --output-sync=target book-committed book-student
	$(MAKE) html-check

bench: $(STAMP)
	MPLBACKEND=Agg $(BIN)/pytest bench -o python_files='bench_*.py' --benchmark-only \
		--benchmark-columns=min,median,max,rounds

# Mutation testing of the methods layer with mutmut (bench/mutation/mutate.py: the modules are
# listed in bench/mutation/modules.toml, the equivalent mutants with their reasons in
# equivalents.toml): each module's mutants against its own tests, then the report
# bench/mutation.md, which bench/mutation/test_report.py checks against the modules as they are.
# Hours on two cores, so not part of `make test`; `make mutate MODULES="newton ode"` runs some.
# `make mutate-check` checks the committed report alone (every module run, each at 90 % or more).
MODULES ?=
mutate: $(STAMP)
	nice -n 5 $(BIN)/python bench/mutation/mutate.py run $(MODULES)
	$(MAKE) mutate-check

mutate-check: $(STAMP)
	$(BIN)/pytest -q bench/mutation/test_report.py

# Recompute every stored certificate (interval proofs of equilibria) into book/certificates/.
certify: $(STAMP)
	$(BIN)/python book/certificates/make_certificates.py

# Re-execute chapters in place after editing them (all of them, or NB=book/<chapter>.ipynb),
# without the execution timings that would dirty the diff.
NB ?= $(wildcard book/*.ipynb)
execute: $(STAMP)
	$(NB_ENV) $(BIN)/python .ci/execute_notebooks.py $(NB)

# The printed book, on A4 paper (`make pdf PAPER=letter`: US Letter), in two editions: the answer
# key, the whole book with its solutions, _build/latex/numerical-methods-for-mechanisms.pdf, and
# the students' edition, without a solution, _build/student/_build/latex/
# numerical-methods-for-mechanisms-student.pdf (both copied into _build/pdf), built side by side;
# both render the committed outputs (strict nbval checks them) without executing the chapters
# again; then their test, tests/test_pdf.py (not part of make test).
# It needs XeLaTeX and its fonts, and poppler's pdftotext for the test, from Debian's packages:
# TEX_PACKAGES below.
TEX_PACKAGES := texlive-xetex texlive-latex-extra texlive-fonts-recommended latexmk \
	fonts-freefont-otf poppler-utils
PAPER ?= a4
PDF_CONFIG := _build/pdf_config.yml
PDF_NAME := numerical-methods-for-mechanisms
ANSWER_KEY := _build/latex/$(PDF_NAME).pdf
STUDENT_PDF := $(STUDENT)/_build/latex/$(PDF_NAME)-student.pdf
pdf:
	@command -v xelatex >/dev/null && command -v latexmk >/dev/null && \
		command -v pdftotext >/dev/null || { echo "make pdf needs XeLaTeX and poppler:" \
		"apt-get install $(TEX_PACKAGES)"; exit 1; }
	@case "$(PAPER)" in a4|letter) ;; *) echo "PAPER is a4 or letter, not $(PAPER)"; exit 1;; esac
	$(MAKE) -j2 --output-sync=target pdf-answer-key pdf-student
	mkdir -p _build/pdf && cp $(ANSWER_KEY) $(STUDENT_PDF) _build/pdf/
	MECHNUM_PDF=$(ANSWER_KEY) MECHNUM_STUDENT_PDF=$(STUDENT_PDF) MECHNUM_PDF_PAPER=$(PAPER) \
		$(BIN)/pytest -rs tests/test_pdf.py

pdf-answer-key: downloads
	$(BIN)/python .ci/book_config.py $(PDF_CONFIG) \
		sphinx.config.latex_elements.papersize=$(PAPER)paper execute.execute_notebooks=off
	$(NB_ENV) $(BIN)/jupyter-book build . --builder pdflatex --config $(PDF_CONFIG)

STUDENT_TEX := [[book/index, $(PDF_NAME)-student.tex, 'Numerical Methods for Mechanisms (student edition)', The mechnum team, manual, false]]
pdf-student: student-src
	$(BIN)/python .ci/book_config.py --from $(STUDENT_SRC)/_config.yml $(STUDENT)/pdf_config.yml \
		sphinx.config.latex_elements.papersize=$(PAPER)paper \
		"sphinx.config.latex_documents=$(STUDENT_TEX)" \
		latex.latex_documents.targetname=$(PDF_NAME)-student.tex
	$(NB_ENV) $(BIN)/jupyter-book build $(STUDENT_SRC) --path-output $(STUDENT) \
		--builder pdflatex --config $(STUDENT)/pdf_config.yml

# JupyterLab with jupyterlab-myst, installed once into .venv from requirements.txt, on the book.
LAB_STAMP := $(VENV)/.lab-installed
$(LAB_STAMP): requirements.txt $(STAMP)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements.txt
	touch $(LAB_STAMP)

lab: $(LAB_STAMP)
	cd book && $(NB_ENV) ../$(BIN)/jupyter lab

clean:
	rm -rf _build .pytest_cache .hypothesis .benchmarks
