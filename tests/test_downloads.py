"""The page "Run the chapters yourself" serves what a reader needs to run every chapter: the wheel
of ``mechnum`` and the chapters with every file they read (the registry, the certificates) and
the bibliography they cite, which work in a fresh environment with nothing else of the book.

Runs on the HTML that ``make book`` writes (``MECHNUM_BUILT_HTML``) and on the student edition
(``MECHNUM_STUDENT_HTML``, ``make book-student``), each skipped without it. For each edition it
takes the wheel and the zip its page links, creates a virtual environment (from the interpreter
that created this one, so no ``mechnum`` is installed in it), installs the served wheel with its
``book`` extra at the book's pins, unpacks the zip and executes every notebook in it, two at a
time (the machine's two cores), each in a fresh kernel of that environment started in the
unpacked folder: a notebook that reads a file the zip lacks, or imports what the wheel lacks,
fails here.
"""

import hashlib
import os
import re
import subprocess
import sys
import zipfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

import mechnum

ROOT = Path(__file__).resolve().parents[1]
EDITIONS = {"book": os.environ.get("MECHNUM_BUILT_HTML"),
            "student": os.environ.get("MECHNUM_STUDENT_HTML")}
WHEEL = f"mechnum-{mechnum.__version__}-py3-none-any.whl"
ZIP = "mechnum-chapters.zip"
PARALLEL = 2
"""Notebooks executed at once: the two cores of the machines the book is tested on."""
TIMEOUT = 600
"""Seconds a cell may run (the longest page takes well under a minute)."""
RUN = """import sys, nbformat
from jupyter_client.kernelspec import KernelSpecManager
from nbclient import NotebookClient
spec = KernelSpecManager().get_kernel_spec("python3")
assert spec.argv[0].startswith(sys.prefix), f"the kernel is not the reader's: {spec.argv}"
nb = nbformat.read(sys.argv[1], as_version=4)
NotebookClient(nb, timeout=int(sys.argv[2]), kernel_name="python3").execute()
print("executed", sum(c.cell_type == "code" for c in nb.cells), "code cells")
"""


def editions():
    return [pytest.param(edition, marks=pytest.mark.skipif(
        not html, reason=f"MECHNUM_{'BUILT' if edition == 'book' else 'STUDENT'}_HTML is not set"))
        for edition, html in EDITIONS.items()]


def served(edition, name):
    """The file of the edition's download link that ends in ``name``."""
    built = Path(EDITIONS[edition])
    page = (built / "book" / "run_yourself.html").read_text(encoding="utf-8")
    links = re.findall(r'href="(\.\./_downloads/[^"]+)"', page)
    found = [link for link in links if link.endswith("/" + name)]
    assert found, f"the page links no {name}: {links}"
    return (built / "book" / found[0]).resolve()


def test_the_extras_pin_the_versions_the_book_is_tested_with():
    import tomllib

    tested = {}
    for name in ("environment.txt", "requirements.txt"):
        for line in (ROOT / name).read_text(encoding="utf-8").splitlines():
            pin = line.split("#")[0].strip()
            if "==" in pin:
                package, release = pin.split("==")
                tested[package.lower()] = release
    project = tomllib.loads((ROOT / "pkg" / "pyproject.toml").read_text(encoding="utf-8"))
    extras = project["project"]["optional-dependencies"]
    assert {"book", "lab"} <= set(extras)  # the grader is the instructors' (course/)
    for extra, requirements in extras.items():
        for requirement in requirements:
            package, _, release = requirement.partition("==")
            assert release and tested.get(package.lower()) == release, (extra, requirement)


@pytest.mark.parametrize("edition", editions())
def test_page_serves_the_wheel_and_the_chapters(edition):
    wheel, chapters = served(edition, WHEEL), served(edition, ZIP)
    with zipfile.ZipFile(wheel) as w:
        assert {"mechnum/__init__.py", "mechnum/newton/__init__.py",
                "mechnum/exercises/__init__.py"} <= set(w.namelist())
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    with zipfile.ZipFile(chapters) as z:
        names = set(z.namelist())
    notebooks = {f"{stem}.ipynb" for stem in re.findall(r"file: book/(\w+)", toc)
                 if (ROOT / "book" / f"{stem}.ipynb").exists()}
    assert notebooks == {name for name in names if name.endswith(".ipynb")}
    certificates = {f"certificates/{p.name}"
                    for p in (ROOT / "book" / "certificates").glob("*.json")}
    assert {"published_values.csv", "findings.csv", "references.bib"} | certificates <= names
    # the one module served is the registry's rules that the chapters import (`published`)
    assert [name for name in names if name.endswith(".py")] == ["published.py"], (
        "build code is served")


@pytest.fixture(scope="module")
def reader(tmp_path_factory):
    """``reader(wheel)``: the Python of a fresh environment with ``wheel[book]`` installed (one
    environment for each distinct wheel)."""
    made = {}

    def make(wheel):
        digest = hashlib.sha256(wheel.read_bytes()).hexdigest()[:16]
        if digest not in made:
            where = tmp_path_factory.mktemp(f"reader-{digest}")
            venv = where / "venv"
            subprocess.run([sys._base_executable, "-m", "venv", str(venv)], check=True)
            python = venv / "bin" / "python"
            pins = where / "pins.txt"  # the book's exact pins, as constraints (no editable line)
            pins.write_text("\n".join(line for line in
                                      (ROOT / "environment.txt").read_text().splitlines()
                                      if "==" in line))
            subprocess.run([str(python), "-m", "pip", "install", "--quiet",
                            "--disable-pip-version-check", f"{wheel}[book]", "nbclient",
                            "nbformat", "-c", str(pins)], check=True)
            subprocess.run([str(python), "-m", "ipykernel", "install", "--sys-prefix", "--name",
                            "python3"], check=True, capture_output=True)
            found = subprocess.run([str(python), "-c", "import mechnum; print(mechnum.__file__)"],
                                   check=True, capture_output=True, text=True).stdout
            assert str(venv) in found  # the reader's copy, not this repository's
            made[digest] = python
        return made[digest]
    return make


def execute(python, notebook, home):
    """Run ``notebook`` top to bottom in a fresh kernel of ``python``'s environment, in the
    notebook's folder; what went wrong, or None."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("MPLBACKEND", "PYTHONPATH", "JUPYTER_PATH", "JUPYTER_DATA_DIR")}
    env["HOME"] = str(home)  # no kernel of the user's own folders can stand in for the reader's
    out = subprocess.run([str(python), "-c", RUN, notebook.name, str(TIMEOUT)],
                         cwd=notebook.parent, env=env, capture_output=True, text=True)
    if out.returncode or not out.stdout.startswith("executed"):
        return f"{notebook.name}:\n{out.stderr[-3000:]}"
    return None


EXECUTED = {}
"""What each notebook run gave, keyed by the digests of the wheel, of the zip's other files and
of the notebook: a notebook that both editions serve byte for byte, beside the same files and
with the same wheel, runs once (the study pages and the appendix, which have no solution)."""


def _digest(*blobs):
    hashed = hashlib.sha256()
    for blob in blobs:
        hashed.update(hashlib.sha256(blob).digest())
    return hashed.hexdigest()


@pytest.mark.parametrize("edition", editions())
def test_every_served_notebook_runs_from_the_zip_with_the_served_wheel(edition, reader,
                                                                       tmp_path):
    wheel = served(edition, WHEEL)
    python = reader(wheel)
    chapters = tmp_path / "chapters"
    with zipfile.ZipFile(served(edition, ZIP)) as z:
        z.extractall(chapters)
    notebooks = sorted(chapters.glob("*.ipynb"))
    assert len(notebooks) >= 15
    files = sorted(p for p in chapters.rglob("*") if p.is_file() and p.suffix != ".ipynb")
    around = _digest(wheel.read_bytes(), *(str(p.relative_to(chapters)).encode() + p.read_bytes()
                                           for p in files))
    keys = {nb: _digest(around.encode(), nb.read_bytes()) for nb in notebooks}
    home = tmp_path / "home"
    home.mkdir()
    to_run = [nb for nb in notebooks if keys[nb] not in EXECUTED]
    with ThreadPoolExecutor(PARALLEL) as pool:
        for nb, failure in zip(to_run, pool.map(lambda nb: execute(python, nb, home), to_run)):
            EXECUTED[keys[nb]] = failure
    failed = [EXECUTED[keys[nb]] for nb in notebooks if EXECUTED[keys[nb]]]
    assert not failed, f"{len(failed)} of {len(notebooks)} notebooks fail:\n" + "\n".join(failed)
