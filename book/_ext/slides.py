"""Slides for each lecture: one reveal.js deck per lecture page, generated from the page as the
book renders it, served offline with the book, and linked from the lecture.

A lecture page is an entry of the numbered part of ``_toc.yml`` (its study page, nested under
it, has no deck). After the HTML build, each lecture's built page is cut into slides by its
headings: a section (``##``) is a column of slides, its subsections (``###``) follow in the same
column. What a slide shows, the section's heading over it, is what a lecturer projects:

* **shown**: display equations, lists (the learning goals), figures with their captions, the
  code of a cell with what it prints (the loop worked by hand, its iteration table), tables,
  the exercises' statements and short admonitions;
* **in the speaker notes** (reveal.js's key ``S``): the prose, which the lecturer says;
* **left out**: the solutions (the slides are projected to the class), the starters and checks of
  the exercises (the page has them), the folded blocks (errata) and animations (played on the
  page; the notes say so).

A section's blocks fill slides in order, :data:`CAPACITY` at most on each (a figure, a code cell,
a table or an exercise weighs :data:`BIG`, an equation or a short list 1); the prose before a
block goes to the notes of the block's slide. Links and images keep pointing into the book.
Equations are typeset by the MathJax the book serves; reveal.js is the npm package that
``make`` installs (``book/_ext/package.json`` pins it, ``package-lock.json`` locks it) and this
extension copies into ``_build/html/slides/revealjs``, so a deck loads nothing from the network.
``tests/test_browser.py`` opens every slide of every deck in headless Chromium.
"""

import copy
import os
import posixpath
import re
import shutil
from pathlib import Path

from bs4 import BeautifulSoup, NavigableString
from docutils import nodes
from sphinx import addnodes
from sphinx.errors import ExtensionError

FOLDER = "slides"
"""The decks' folder in the built book: ``slides/<lecture>.html``."""
REVEAL_FILES = ("dist/reveal.js", "dist/reveal.css", "dist/theme/white.css",
                "dist/plugin/notes.js", "LICENSE")
"""What a deck uses of the reveal.js package, copied into ``slides/revealjs`` (``dist/``
dropped)."""
BIG, CAPACITY = 4, 4
"""A figure, code cell, table or exercise fills a slide (:data:`BIG`); equations and lists
weigh 1, so up to :data:`CAPACITY` of them share one."""
LIST_WORDS = 90
"""A list of more words than this is prose: it goes to the speaker notes."""
NOTE_WORDS = 80
"""An admonition (not an exercise) of more words than this goes to the speaker notes."""
SIZE = (1280, 720)
"""The slides' size in CSS pixels, 16:9; reveal.js scales them to the screen."""
WIDE_CODE = 32
"""A code cell whose input and output have more lines than this shows them on two slides."""

STYLE = """\
.reveal { font-size: 30px; }
.reveal .slides { text-align: left; }
.reveal h1 { font-size: 1.7em; text-transform: none; }
.reveal h2 { font-size: 1.25em; text-transform: none; margin-bottom: 0.4em; }
.reveal .deck-title { text-align: center; }
.reveal .deck-title p { font-size: 0.8em; }
.reveal .section-number { color: #666; }
.reveal ul, .reveal ol { display: block; margin-left: 1.2em; font-size: 0.85em; }
.reveal li p { margin: 0.1em 0; }
.reveal div.math { font-size: 0.85em; margin: 0.3em 0; }
.reveal figure { margin: 0; text-align: center; }
.reveal figure img { max-height: 470px; max-width: 100%; margin: 0; }
.reveal figcaption { font-size: 0.55em; text-align: left; }
.reveal pre { width: 100%; margin: 0.2em 0; font-size: 0.5em; max-height: 560px;
              box-shadow: none; }
.reveal pre.output { background: #f6f6f6; border-left: 4px solid #bbb; }
.reveal .table-block { font-size: 0.5em; max-height: 560px; overflow: auto; }
.reveal .table-block table { margin: 0; }
.reveal .table-block td, .reveal .table-block th { padding: 0.15em 0.4em; }
.reveal .table-block p { margin: 0; }
.reveal .box { border-left: 5px solid #2a76dd; padding: 0.2em 0.6em; font-size: 0.7em;
               background: #f3f7fd; max-height: 560px; overflow: auto; }
.reveal .box .admonition-title { font-weight: bold; margin: 0; }
.reveal .lead { font-size: 0.8em; color: #333; }
.reveal .back { float: right; font-size: 0.4em; font-weight: normal; margin-top: 0.6em; }
"""

PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Slides: {title}</title>
<link rel="stylesheet" href="revealjs/reveal.css">
<link rel="stylesheet" href="revealjs/white.css">
<link rel="stylesheet" href="{pygments}">
<link rel="stylesheet" href="slides.css">
<script>window.MathJax = {{"options": {{"processHtmlClass": "math"}}}}</script>
<script defer src="{mathjax}"></script>
</head>
<body>
<div class="reveal"><div class="slides">
{slides}
</div></div>
<script src="revealjs/reveal.js"></script>
<script src="revealjs/notes.js"></script>
<script>
Reveal.initialize({{hash: true, slideNumber: "c/t", width: {width}, height: {height},
                   margin: 0.04, center: false, plugins: [RevealNotes]}});
</script>
</body>
</html>
"""


def revealjs_folder(srcdir):
    """Where the reveal.js package is: ``MECHNUM_REVEALJS``, else what ``make`` installs
    (``.venv/npm/node_modules/reveal.js`` beside ``_config.yml``)."""
    named = os.environ.get("MECHNUM_REVEALJS")
    folder = Path(named) if named else Path(srcdir) / ".venv" / "npm" / "node_modules" / "reveal.js"
    if not (folder / "dist" / "reveal.js").is_file():
        raise ExtensionError(f"reveal.js is not installed at {folder}: `make book` installs it "
                             "from the npm registry (npm ci, book/_ext/package-lock.json)")
    return folder


def lectures(env):
    """The lecture pages: the entries of the root page's numbered table of contents."""
    found = []
    for toctree in env.get_doctree(env.config.root_doc).findall(addnodes.toctree):
        if toctree.get("numbered"):
            found += [name for name in toctree["includefiles"] if name not in found]
    return found


def deck_uri(docname):
    """The deck's address relative to its lecture's page."""
    return posixpath.relpath(f"{FOLDER}/{posixpath.basename(docname)}.html",
                             posixpath.dirname(docname) or ".")


def _link_the_deck(app, doctree, docname):
    """Under a lecture's title: a paragraph that links its deck (HTML builds only)."""
    if app.builder.format != "html" or docname not in lectures(app.env):
        return
    section = next(doctree.findall(nodes.section), None)
    if section is None:
        return
    link = nodes.reference("", "Slides of this lecture", refuri=deck_uri(docname),
                           classes=["lecture-slides"])
    paragraph = nodes.paragraph("", "", link, nodes.Text(
        " (reveal.js, offline; press S for the speaker notes, which hold the prose)"),
        classes=["lecture-slides"])
    section.insert(1, paragraph)


def _words(tag):
    return len(tag.get_text(" ", strip=True).split())


def _classes(tag):
    return set(tag.get("class") or [])


class Block:
    """One thing a slide shows: its HTML and its weight."""

    def __init__(self, html, weight):
        # a section inside a block (an exercise's body) would be a slide to reveal.js
        self.html, self.weight = re.sub(r"<(/?)section\b", r"<\1div", html), weight


class Slide:
    def __init__(self, title):
        self.title, self.blocks, self.notes = title, [], []

    @property
    def weight(self):
        return sum(b.weight for b in self.blocks)

    def html(self, back):
        notes = "\n".join(self.notes)
        body = "\n".join(b.html for b in self.blocks)
        if not self.blocks:
            body = f'<p class="lead">{_lead(self.notes)}</p>'
        return (f'<section>\n<h2>{self.title}<a class="back" href="{back}">on the page</a></h2>'
                f"\n{body}\n"
                + (f'<aside class="notes">\n{notes}\n</aside>\n' if notes else "")
                + "</section>")


def _lead(notes):
    """The first sentence of the notes, for a slide that has nothing else to show."""
    text = BeautifulSoup("".join(notes), "html.parser")
    first = text.find("p") or text
    sentence = re.split(r"(?<=[.:;!?])\s", first.decode_contents().strip(), maxsplit=1)[0]
    return sentence or "&nbsp;"


def _code_blocks(cell):
    """A code cell as blocks: its code and what it prints (text or a table)."""
    code = cell.select_one("div.cell_input pre")
    hidden = "tag_hide-input" in _classes(cell) or "tag_remove-input" in _classes(cell)
    outputs = cell.select("div.cell_output pre")
    tables = cell.select("div.cell_output table")
    pieces = [] if hidden or code is None else [f'<div class="highlight">{code}</div>']
    for pre in outputs:
        pre["class"] = list(_classes(pre) | {"output"})
        pieces.append(f'<div class="highlight">{pre}</div>')
    lines = sum(p.count("\n") for p in pieces)
    blocks = ([Block(p, BIG) for p in pieces] if lines > WIDE_CODE
              else [Block("\n".join(pieces), BIG)] if pieces else [])
    blocks += [Block(f'<div class="table-block">{table}</div>', BIG) for table in tables]
    return blocks


def _box(tag):
    return f'<div class="box">{tag.decode_contents()}</div>'


def read_section(section):
    """The items of a section, in order: a :class:`Block`, a note (prose, a string) or a
    subsection (a ``<section>``)."""
    items, after_exercise = [], False
    for child in section.children:
        if isinstance(child, NavigableString):
            continue
        classes = _classes(child)
        if child.name == "section":
            items.append(child)
        elif re.fullmatch(r"h\d", child.name) or child.name == "span" and "target" in classes:
            continue
        elif child.name == "div" and "math" in classes:
            items.append(Block(str(child), 1))
        elif child.name in ("ul", "ol"):
            items.append(Block(str(child), 1 + len(child.find_all("li")) // 4)
                         if _words(child) <= LIST_WORDS else str(child))
        elif child.name == "figure":
            items.append(Block(str(child), BIG))
        elif child.name == "div" and "cell" in classes:
            if after_exercise:
                continue              # the exercise's starter and check: on the page
            if child.select_one("div.animation"):
                items.append("<p>(An animation plays here on the lecture page.)</p>")
            elif child.select_one("figure, img"):
                items += [Block(str(f), BIG) for f in child.select("figure")
                          or child.select("img")]
            else:
                items += _code_blocks(child)
        elif child.name == "div" and "admonition" in classes:
            if "solution" in classes or "dropdown" in classes:
                continue              # solutions, folded blocks: on the page only
            if "exercise" in classes:
                after_exercise = True
                items.append(Block(_box(child), BIG))
            elif _words(child) <= NOTE_WORDS:
                items.append(Block(_box(child), 1))
            else:
                items.append(str(child))
        elif child.name == "div" and child.select_one("table"):
            items.append(Block(f'<div class="table-block">{child.select_one("table")}</div>',
                               BIG))
        elif child.get_text(strip=True):
            items.append(str(child))
    return items


def _title(section):
    heading = section.find(re.compile(r"h\d"))
    heading = copy.copy(heading)
    for link in heading.select("a.headerlink"):
        link.decompose()
    return heading.decode_contents().strip()


def section_slides(section, title=None):
    """The slides of a section and of its subsections, in order."""
    title = title or _title(section)
    slides, pending, current = [], [], None
    for item in read_section(section):
        if isinstance(item, str):
            pending.append(item)
        elif isinstance(item, Block):
            if current is None or current.blocks and current.weight + item.weight > CAPACITY:
                current = Slide(title)
                slides.append(current)
            current.notes += pending
            current.blocks.append(item)
            pending = []
        else:
            if pending:
                if current is None:
                    current = Slide(title)
                    slides.append(current)
                current.notes += pending
                pending = []
            slides += section_slides(item)
            current = None
    if pending:
        if current is None:
            current = Slide(title)
            slides.append(current)
        current.notes += pending
    return slides


def _relink(soup, page_dir, deck_dir, page):
    """Point the relative links and images of a page's HTML, moved into the deck, at the same
    files; a link within the page goes back to the page."""
    for tag, attribute in (("a", "href"), ("img", "src")):
        for element in soup.find_all(tag):
            url = element.get(attribute)
            if not url or re.match(r"^[a-z]+:|^/", url):
                continue
            if url.startswith("#"):
                url = page + url
            target = posixpath.normpath(posixpath.join(page_dir, url))
            element[attribute] = posixpath.relpath(target, deck_dir)
    for element in soup.find_all(id=True):
        del element["id"]


def make_deck(html, docname, number):
    """The reveal.js deck (its HTML) of a lecture's built page ``html``."""
    soup = BeautifulSoup(html, "html.parser")
    article = soup.select_one("article")
    mathjax = soup.find("script", src=re.compile(r"mathjax"))
    if article is None or mathjax is None:
        raise ExtensionError(f"{docname}: no article, or no MathJax, in its built page")
    page_dir = posixpath.dirname(docname)
    page = posixpath.basename(docname) + ".html"
    script = posixpath.normpath(posixpath.join(page_dir, mathjax["src"].split("?")[0]))
    for link in article.select("a.headerlink"):
        link.decompose()
    _relink(article, page_dir, FOLDER, page)
    top = article.find("section")
    title = _title(top)
    back = posixpath.relpath(docname + ".html", FOLDER)
    plain = BeautifulSoup(title, "html.parser").get_text(" ", strip=True)
    columns = [f'<section class="deck-title"><h1>{title}</h1>\n'
               f"<p>Lecture {number} of <em>Numerical Methods for Mechanisms</em></p>\n"
               f'<p><a href="{back}">the lecture page</a> &middot; press S for the speaker '
               f"notes</p></section>"]
    for part in [top, *top.find_all("section", recursive=False)]:
        if part is top:
            intro = copy.copy(top)
            for sub in intro.find_all("section", recursive=False):
                sub.decompose()
            slides = section_slides(intro, title)
        else:
            slides = section_slides(part)
        if slides:
            inner = "\n".join(s.html(back) for s in slides)
            columns.append(f"<section>\n{inner}\n</section>")
    return PAGE.format(title=plain, mathjax=posixpath.relpath(script, FOLDER),
                       pygments=posixpath.relpath("_static/pygments.css", FOLDER),
                       slides="\n".join(columns), width=SIZE[0], height=SIZE[1])


def write_decks(app, exception):
    """After an HTML build: every lecture's deck, reveal.js and the decks' style sheet."""
    if exception is not None or app.builder.format != "html":
        return
    source = revealjs_folder(app.srcdir)
    out = Path(app.outdir) / FOLDER
    (out / "revealjs").mkdir(parents=True, exist_ok=True)
    for name in REVEAL_FILES:
        shutil.copyfile(source / name, out / "revealjs" / Path(name).name)
    (out / "slides.css").write_text(STYLE, encoding="utf-8")
    numbers = app.env.toc_secnumbers
    for docname in lectures(app.env):
        page = Path(app.outdir) / f"{docname}.html"
        number = ".".join(map(str, numbers.get(docname, {}).get("", ()))) or "?"
        deck = make_deck(page.read_text(encoding="utf-8"), docname, number)
        (out / f"{posixpath.basename(docname)}.html").write_text(deck, encoding="utf-8")


def setup(app):
    app.connect("doctree-resolved", _link_the_deck)
    app.connect("build-finished", write_decks)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
