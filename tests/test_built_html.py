"""The built book works offline (no page loads a script or a stylesheet from the network), and
its mathematics is rendered (no TeX is left in the text outside MathJax's math elements).

Runs on the HTML that ``make book`` (or ``make book-committed``) writes (``make html-check``
points ``MECHNUM_BUILT_HTML`` at it); the tests of built pages are skipped when that variable is
unset, as in the unit-test run that precedes the build. The page *Execution statistics* shows
what was measured.
"""

import os
import re
import sys
from html.parser import HTMLParser
from pathlib import Path

import pytest

BUILT = os.environ.get("MECHNUM_BUILT_HTML")
ROOT = Path(__file__).resolve().parents[1]
needs_build = pytest.mark.skipif(not BUILT, reason="MECHNUM_BUILT_HTML is not set")
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


class VisibleText(HTMLParser):
    """The text a reader sees as prose: outside scripts, styles, code and MathJax's math."""

    HIDDEN = {"script", "style", "pre", "code", "textarea", "kbd", "samp"}
    VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source",
            "track", "wbr"}

    def __init__(self):
        super().__init__()
        self.text, self._stack = [], []

    def handle_starttag(self, tag, attrs):
        if tag in self.VOID:
            return
        classes = (dict(attrs).get("class") or "").split()
        self._stack.append(tag in self.HIDDEN or "math" in classes)

    def handle_endtag(self, tag):
        if tag not in self.VOID and self._stack:
            self._stack.pop()

    def handle_data(self, data):
        if not any(self._stack):
            self.text.append(data)


# TeX that escaped MathJax: a control word (\theta, \frac), a math delimiter, or a sub/superscript
# in braces. Prose never contains these; code and math elements are skipped.
LEFT_TEX = re.compile(r"\\[A-Za-z]{2,}|\\[()\[\]]|\$[^$\s]|[_^]\{")


def pages():
    return sorted(Path(BUILT).rglob("*.html")) if BUILT else []


@needs_build
def test_the_book_was_built():
    names = {p.name for p in pages()}
    assert {"index.html", "01_newton_hacksaw.html", "published_values.html", "api.html"} <= names


@needs_build
@pytest.mark.parametrize("page", pages(), ids=lambda p: str(p.relative_to(BUILT)))
def test_page_loads_nothing_remote(page):
    parser = Resources()
    parser.feed(page.read_text(encoding="utf-8"))
    remote = [url for url in parser.loaded if REMOTE.match(url)]
    assert not remote, f"{page.name} loads {remote}"


@needs_build
def test_mathjax_is_served_by_the_book():
    parser = Resources()
    parser.feed((Path(BUILT) / "book" / "01_newton_hacksaw.html").read_text(encoding="utf-8"))
    mathjax = [url for url in parser.loaded if "mathjax" in url.lower()]
    assert mathjax, "the chapter loads no MathJax"
    for url in mathjax:
        assert (Path(BUILT) / "book" / url.split("?")[0]).resolve().exists(), url


@needs_build
@pytest.mark.parametrize("page", pages(), ids=lambda p: str(p.relative_to(BUILT)))
def test_no_tex_is_left_outside_mathjax(page):
    parser = VisibleText()
    parser.feed(page.read_text(encoding="utf-8"))
    text = " ".join(parser.text)
    left = [text[max(0, m.start() - 40):m.end() + 40] for m in LEFT_TEX.finditer(text)]
    assert not left, f"{page.name}: TeX outside the math elements: {left[:5]}"


def test_the_tex_detector_finds_a_broken_passage():
    # a Markdown list item made of the tail of an inline formula, beside math and code that are fine
    parser = VisibleText()
    parser.feed('<p>The angle <span class="math">\\(\\theta_1\\)</span> is fine, <code>a_{1}</code>'
                ' too.<br></p><ul><li><p>+ A_r\\sin\\theta_1 + 2$. The annex</p></li></ul>')
    assert LEFT_TEX.findall(" ".join(parser.text)) == ["\\sin", "\\theta", "$."]


@needs_build
def test_the_execution_page_shows_what_was_measured():
    """Every table of the page *Execution statistics* lists every notebook of the book, each with
    the wall and CPU times of a record of the notebook as it is now (book/_ext)."""
    sys.path.insert(0, str(ROOT / "book" / "_ext"))
    from execution_statistics import measured

    page = (Path(BUILT) / "book" / "execution.html").read_text(encoding="utf-8")
    tables = re.findall(r"<table.*?</table>", page, re.DOTALL)
    assert tables, "the page shows no measurement"
    notebooks = sorted(p.stem for p in (ROOT / "book").glob("*.ipynb"))
    for table in tables:
        rows = [[re.sub(r"<[^>]+>", "", cell).strip() for cell in
                 re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", row, re.DOTALL)]
                for row in re.findall(r"<tr.*?</tr>", table, re.DOTALL)[1:]]
        assert sorted(row[0] for row in rows) == notebooks
        for name, wall, cpu, _ in rows:
            shown = {(f"{r['wall']:.1f}", f"{r['cpu']:.1f}")
                     for _, r in measured(ROOT, f"book/{name}.ipynb")}
            assert (wall, cpu) in shown, f"{name}: {wall} s, {cpu} s measured by no run"


def _lectures():
    sys.path.insert(0, str(ROOT / "tests"))
    from lecture_pages import lectures

    return list(lectures())


@needs_build
def test_every_lecture_links_its_deck_of_slides():
    """Seven decks, one per lecture page, each linked from the top of its lecture (before its
    first section) and loading reveal.js and MathJax from the built book."""
    decks = sorted(p.stem for p in (Path(BUILT) / "slides").glob("*.html"))
    assert decks == sorted(Path(lecture).name for lecture in _lectures())
    for lecture in _lectures():
        page = (Path(BUILT) / f"{lecture}.html").read_text(encoding="utf-8")
        link = re.search(r'<a class="[^"]*lecture-slides[^"]*" href="([^"]+)"', page)
        assert link, f"{lecture} links no slides"
        article = page[page.index("<article"):]
        sections = [m.start() for m in re.finditer("<section", article)]
        assert sections[0] < article.index(link.group(0)) < sections[1], "not under the title"
        deck = (Path(BUILT) / lecture).parent / link.group(1)
        assert deck.resolve() == (Path(BUILT) / "slides" / f"{Path(lecture).name}.html").resolve()
        parser = Resources()
        parser.feed(deck.read_text(encoding="utf-8"))
        for url in parser.loaded:
            assert (deck.parent / url).resolve().is_file(), f"{deck.name} loads {url}"
        assert any("reveal.js" in url for url in parser.loaded)
        assert any("mathjax" in url for url in parser.loaded)


@needs_build
def test_the_instructors_page_is_in_the_contents_and_numbers_exercises_as_the_book():
    """The page for instructors is in the book's table of contents (its sidebar), and each
    exercise of its plan of the term links to the exercise that the lecture numbers so."""
    index = (Path(BUILT) / "book" / "index.html").read_text(encoding="utf-8")
    assert 'href="instructors.html"' in index
    page = (Path(BUILT) / "book" / "instructors.html").read_text(encoding="utf-8")
    plan = page[page.index("term-plan"):]
    plan = plan[:plan.index("</table>")]
    links = re.findall(r'href="([\w.]+)#([\w-]+)"><span[^>]*>(\d+\.\d+)</span>', plan)
    assert len(links) >= 7 * 3, f"{len(links)} exercises in the plan"
    for target, label, number in links:
        lecture = (Path(BUILT) / "book" / target).read_text(encoding="utf-8")
        caption = re.search(rf'id="{label}">\s*<p class="admonition-title">'
                            r'<span class="caption-number">Exercise ([\d.]+)', lecture)
        assert caption and caption.group(1) == number, (target, label, number)
    assert len(re.findall(r'href="\.\./slides/\w+\.html"', plan)) == len(_lectures())
