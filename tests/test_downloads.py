"""The page "Run the chapters yourself" serves what a reader needs to run a chapter: the wheel of
``mechnum`` and the chapters with the registry they read and the bibliography they cite, which
work in a fresh environment with nothing else of the book.

Runs on the HTML that ``make book`` writes (``MECHNUM_BUILT_HTML``); skipped without it. It
creates a virtual environment (the interpreter that created this one, so no ``mechnum`` is
installed in it), installs the served wheel with its ``book`` extra at the book's pins, and
executes Chapter 1 from the served zip.
"""

import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import mechnum

BUILT = os.environ.get("MECHNUM_BUILT_HTML")
ROOT = Path(__file__).resolve().parents[1]
built = pytest.mark.skipif(not BUILT, reason="MECHNUM_BUILT_HTML is not set")
WHEEL = f"mechnum-{mechnum.__version__}-py3-none-any.whl"
CHAPTER = "01_newton_hacksaw.ipynb"
RUN = """import sys, nbformat
from nbclient import NotebookClient
nb = nbformat.read(sys.argv[1], as_version=4)
NotebookClient(nb, timeout=600, kernel_name="python3").execute()
print("executed", sum(c.cell_type == "code" for c in nb.cells), "code cells")
"""


def served(name):
    """The file of the built page's download link that ends in ``name``."""
    page = (Path(BUILT) / "book" / "run_yourself.html").read_text(encoding="utf-8")
    links = re.findall(r'href="(\.\./_downloads/[^"]+)"', page)
    found = [link for link in links if link.endswith("/" + name)]
    assert found, f"the page links no {name}: {links}"
    return (Path(BUILT) / "book" / found[0]).resolve()


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


@built
def test_page_serves_the_wheel_and_the_chapters():
    wheel, chapters = served(WHEEL), served("mechnum-chapters.zip")
    assert wheel.exists() and chapters.exists()
    with zipfile.ZipFile(wheel) as w:
        assert {"mechnum/__init__.py", "mechnum/newton/__init__.py",
                "mechnum/exercises/__init__.py"} <= set(w.namelist())
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    with zipfile.ZipFile(chapters) as z:
        names = set(z.namelist())
    for stem in re.findall(r"file: book/(\w+)", toc):
        if (ROOT / "book" / f"{stem}.ipynb").exists():
            assert f"{stem}.ipynb" in names
    assert {"published_values.csv", "findings.csv", "references.bib"} <= names


@built
def test_a_downloaded_chapter_runs_with_the_downloaded_wheel(tmp_path):
    venv = tmp_path / "reader"
    subprocess.run([sys._base_executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    pins = tmp_path / "pins.txt"  # the book's exact pins, as constraints (no editable line)
    pins.write_text("\n".join(line for line in (ROOT / "environment.txt").read_text().splitlines()
                              if "==" in line))
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                    f"{served(WHEEL)}[book]", "nbclient", "nbformat", "-c", str(pins)],
                   check=True)
    subprocess.run([str(python), "-m", "ipykernel", "install", "--sys-prefix", "--name",
                    "python3"], check=True, capture_output=True)
    chapters = tmp_path / "chapters"
    with zipfile.ZipFile(served("mechnum-chapters.zip")) as z:
        z.extractall(chapters)
    where = subprocess.run([str(python), "-c", "import mechnum; print(mechnum.__file__)"],
                           check=True, capture_output=True, text=True).stdout
    assert str(venv) in where  # the reader's copy, not this repository's
    env = {k: v for k, v in os.environ.items() if k not in ("MPLBACKEND", "PYTHONPATH")}
    out = subprocess.run([str(python), "-c", RUN, CHAPTER], cwd=chapters, env=env, check=True,
                         capture_output=True, text=True)
    assert out.stdout.startswith("executed")
