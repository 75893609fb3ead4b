"""The built book works offline: no page loads a script or a stylesheet from the network.

Runs on the HTML that ``make book`` writes (``make html-check`` points ``MECHNUM_BUILT_HTML`` at
it); skipped when that variable is unset, as in the unit-test run that precedes the build.
"""

import os
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

BUILT = os.environ.get("MECHNUM_BUILT_HTML")
pytestmark = pytest.mark.skipif(not BUILT, reason="MECHNUM_BUILT_HTML is not set")
REMOTE = re.compile(r"^\s*(https?:)?//", re.IGNORECASE)


class Resources(HTMLParser):
    """Collects the URLs a page loads: scripts, stylesheets, and ``@import``/``url()`` in styles."""

    def __init__(self):
        super().__init__()
        self.loaded, self._in_style = [], False

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "script" and attrs.get("src"):
            self.loaded.append(attrs["src"])
        if tag == "link" and "stylesheet" in (attrs.get("rel") or "") and attrs.get("href"):
            self.loaded.append(attrs["href"])
        self._in_style = tag == "style"

    def handle_data(self, data):
        if self._in_style:
            self.loaded += re.findall(r"""url\(\s*['"]?([^'")]+)""", data)
            self.loaded += re.findall(r"""@import\s+['"]([^'"]+)""", data)


def pages():
    return sorted(Path(BUILT).rglob("*.html")) if BUILT else []


def test_the_book_was_built():
    names = {p.name for p in pages()}
    assert {"index.html", "01_newton_hacksaw.html", "published_values.html", "api.html"} <= names


@pytest.mark.parametrize("page", pages(), ids=lambda p: str(p.relative_to(BUILT)))
def test_page_loads_nothing_remote(page):
    parser = Resources()
    parser.feed(page.read_text(encoding="utf-8"))
    remote = [url for url in parser.loaded if REMOTE.match(url)]
    assert not remote, f"{page.name} loads {remote}"


def test_mathjax_is_served_by_the_book():
    parser = Resources()
    parser.feed((Path(BUILT) / "book" / "01_newton_hacksaw.html").read_text(encoding="utf-8"))
    mathjax = [url for url in parser.loaded if "mathjax" in url.lower()]
    assert mathjax, "the chapter loads no MathJax"
    for url in mathjax:
        assert (Path(BUILT) / "book" / url.split("?")[0]).resolve().exists(), url
