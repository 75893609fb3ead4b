"""The release is written once: the package's version, the citation file and the book's footer
agree, so an instructor who cites the book cites the code that computed it."""

import re
from importlib.metadata import version
from pathlib import Path

import yaml

import mechnum

ROOT = Path(__file__).resolve().parents[1]


def test_installed_version_is_the_package_version():
    assert version("mechnum") == mechnum.__version__


def test_citation_and_footer_name_the_release():
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    footer = config["html"]["extra_footer"]
    assert citation["version"] == mechnum.__version__
    released = str(citation["date-released"])
    assert re.fullmatch(r"\d{4}-\d{2}-\d{2}", released)
    assert f"Version {mechnum.__version__} ({released})" in footer
    assert set(citation["license"]) == {"MIT", "CC-BY-4.0"}
    assert (ROOT / "LICENSE").exists() and (ROOT / "LICENSE-TEXT.md").exists()


def pins(path):
    lines = [line.split("#")[0].strip() for line in path.read_text().splitlines()]
    return [line for line in lines if line]


def test_every_dependency_is_pinned_and_requirements_extend_the_environment():
    environment = pins(ROOT / "environment.txt")
    assert environment[-2:] == ["-e ./course", "-e ./pkg"]  # the instructors' package, the book's
    assert all(re.fullmatch(r"[A-Za-z0-9_.-]+==[0-9][0-9A-Za-z.]*", p) for p in environment[:-2])
    requirements = pins(ROOT / "requirements.txt")
    assert requirements[0] == "-r environment.txt"  # the same pins, by construction
    assert all("==" in p for p in requirements[1:])


def test_the_download_page_names_this_release():
    page = (ROOT / "book" / "run_yourself.md").read_text(encoding="utf-8")
    wheels = set(re.findall(r"mechnum-[0-9][^ \"<>\[]*\.whl", page))
    assert wheels == {f"mechnum-{mechnum.__version__}-py3-none-any.whl"}
