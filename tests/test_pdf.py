"""The printed books that `make pdf` builds: the answer key and the students' edition (skipped
without them: `make test` needs no TeX).

`make pdf` runs this module on the PDFs it has just built: ``MECHNUM_PDF`` (the answer key, the
whole book) and ``MECHNUM_STUDENT_PDF`` (the students' edition, without a solution), on the paper
``MECHNUM_PDF_PAPER``, ``a4`` or ``letter``; the tests of an edition whose PDF is not given are
skipped. It reads each PDF as a reader would, through poppler's ``pdftotext``, and the LaTeX log
beside it:

* the page count lies in :data:`PAGES` and every page has the paper asked for;
* no line of the LaTeX log is overfull by more than :data:`OVERFULL_PT`: nothing runs into the
  margin or off the page;
* the page after the title says which edition it is, under which licences it may be copied,
  how to cite it (``CITATION.cff``) and where the book and its sources live;
* the preface comes first, with every section of the root page;
* the chapters are numbered, the appendices lettered (A, B, ...), the pages left out of the
  printed book (``latex_exclude_docs``) absent;
* no page holds only a heading (a heading is kept with what follows it);
* no code that the web book hides (``hide-input``: the code that builds a table) is printed;
* every table with a verdict and a finding column that the printed book prints (a reproduction
  table, the appendix's summaries) prints every row, with its verdict and its finding, within
  the pages of its chapter or appendix;
* the students' edition holds no solution: the text of its pages holds no line of any
  solution's code, which the answer key prints.
"""

import os
import re
import shutil
import subprocess
from collections import Counter
from pathlib import Path

import nbformat
import pytest
import yaml
from lecture_pages import lectures
from published import VERDICTS
from test_student_edition import solution_code

ROOT = Path(__file__).resolve().parents[1]
EDITIONS = {"answer key": os.environ.get("MECHNUM_PDF"),
            "student": os.environ.get("MECHNUM_STUDENT_PDF")}
PAPER = os.environ.get("MECHNUM_PDF_PAPER", "a4")
PAGES = range(170, 260)
"""The page count of each printed book (on A4, when this test was written: 235 pages for the
answer key, 223 for the students' edition): its chapters and appendices without the API
reference (142 pages alone), with the registry's appendix as a summary per chapter (14 pages;
88 when it printed every row)."""
OVERFULL_PT = 20.0
PAPER_PT = {"a4": (595.3, 841.9), "letter": (612.0, 792.0)}
NUMBERS = ("ONE", "TWO", "THREE", "FOUR", "FIVE", "SIX", "SEVEN", "EIGHT", "NINE", "TEN",
           "ELEVEN", "TWELVE")
"""How the chapter openings spell their numbers (Sphinx's LaTeX, fncychap's Bjarne style)."""


def _editions():
    return [pytest.param(edition, marks=pytest.mark.skipif(
        not (path and Path(path).is_file()), reason=f"no PDF of the {edition} given: make pdf "
        "sets MECHNUM_PDF and MECHNUM_STUDENT_PDF to the PDFs it builds"))
        for edition, path in EDITIONS.items()]


@pytest.fixture(scope="module", params=_editions())
def edition(request):
    return request.param


@pytest.fixture(scope="module")
def pdf(edition):
    return Path(EDITIONS[edition])


def _run(*command):
    if shutil.which(command[0]) is None:
        pytest.fail(f"{command[0]} is missing: apt-get install poppler-utils")
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


@pytest.fixture(scope="module")
def pages(pdf):
    """The text of each page."""
    return read_pages(pdf)


def read_pages(pdf):
    return _run("pdftotext", "-raw", "-enc", "UTF-8", str(pdf), "-").split("\f")[:-1]


def squeeze(text):
    """Text without its spaces, line ends, hyphens, dashes, quotes and Markdown marks, so that a
    cell's text matches however its column wrapped it (pdftotext joins a word hyphenated at a
    line's end) and however LaTeX set its quotes.

    Examples
    --------
    >>> squeeze("not-\\nreproduced ch1-final-motor-\\nspeed, \u2018Posici\u00f3n\u2019")
    'notreproducedch1finalmotorspeed,Posición'
    """
    return re.sub(r"[\s\-\u00ad\u2010-\u2015'\u2018\u2019\"\u201c\u201d`*\\\\]+", "", text)


def _toc():
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    left_out = set(config["sphinx"]["config"].get("latex_exclude_docs", []))
    numbered = [part for part in toc["parts"] if part.get("numbered")]
    after = toc["parts"][toc["parts"].index(numbered[0]) + 1:]
    appendices = [c["file"] for part in after if not part.get("numbered")
                  for c in part["chapters"] if c["file"] not in left_out]
    return toc, numbered[0]["chapters"], appendices, left_out


def _source(docname):
    """A page's cells (none for a Markdown page) and its Markdown text."""
    notebook, markdown = ((ROOT / docname).with_suffix(s) for s in (".ipynb", ".md"))
    if notebook.is_file():
        cells = nbformat.read(notebook, as_version=4).cells
        return cells, "\n".join(c.source for c in cells if c.cell_type == "markdown")
    return [], markdown.read_text(encoding="utf-8")


def _title(docname):
    return re.search(r"^# (.+)$", _source(docname)[1], re.M).group(1).strip()


def _openings(pages, word):
    """The indices of the pages that open a chapter (``CHAPTER``) or an appendix."""
    return [k for k, page in enumerate(pages) if page.lstrip().startswith(word + "\n")]


def _chapter_pages(pages, number):
    starts = _openings(pages, "CHAPTER") + _openings(pages, "APPENDIX") + [len(pages)]
    first = _openings(pages, "CHAPTER")[number - 1]
    return pages[first:min(s for s in starts if s > first)]


def test_page_count_and_paper(pdf):
    info = _run("pdfinfo", "-f", "1", "-l", "9999", str(pdf))
    count = int(re.search(r"^Pages:\s+(\d+)", info, re.M).group(1))
    assert count in PAGES, f"{count} pages, expected {PAGES.start} to {PAGES.stop - 1}"
    sizes = set(re.findall(r"^Page\s+\d+ size:\s+([\d.]+) x ([\d.]+) pts", info, re.M))
    expected = PAPER_PT[PAPER]
    for width, height in sizes:
        upright = sorted((float(width), float(height)))   # a turned page is the same paper
        assert upright == pytest.approx(sorted(expected), abs=1.0), \
            f"a page of {width} x {height} pt, not {PAPER}"


def test_no_line_runs_into_the_margin(pdf):
    log = pdf.with_suffix(".log").read_text(encoding="utf-8", errors="replace")
    overfull = [(float(pt), where) for pt, where in
                re.findall(r"Overfull \\hbox \(([\d.]+)pt too wide\) (.*)", log)]
    assert "Output written" in log, "the LaTeX log is not that of a finished run"
    worst = max(overfull, default=(0.0, "none"))
    assert worst[0] <= OVERFULL_PT, f"a line {worst[0]} pt too wide, {worst[1]}"


def test_preface_first_with_its_sections(pages):
    toc, chapters, _, _ = _toc()
    first_chapter = _openings(pages, "CHAPTER")[0]
    front = squeeze("".join(pages[:first_chapter])).lower()
    opening = _openings(pages, "PREFACE")
    assert opening and opening[0] < first_chapter, "no preface before Chapter 1"
    for heading in re.findall(r"^## (.+)$", _source(toc["root"])[1], re.M):
        assert squeeze(heading).lower() in front, f"the preface lacks its section {heading!r}"


def test_chapters_numbered_and_appendices_lettered(pages):
    _, chapters, appendices, left_out = _toc()
    chapter_openings = _openings(pages, "CHAPTER")
    appendix_openings = _openings(pages, "APPENDIX")
    assert len(chapter_openings) == len(chapters)
    assert [pages[k].split()[1] for k in chapter_openings] == list(NUMBERS[:len(chapters)])
    assert len(appendix_openings) == len(appendices)
    assert max(chapter_openings) < min(appendix_openings)
    letters = [pages[k].split()[1] for k in appendix_openings]
    assert letters == [chr(ord("A") + k) for k in range(len(appendices))]
    for k, docname in zip(appendix_openings, appendices):
        assert squeeze(_title(docname)).lower() in squeeze(pages[k]).lower(), docname
    for docname in left_out:
        title = squeeze(_title(docname)).lower()
        for k in chapter_openings + appendix_openings:
            assert title not in squeeze(pages[k][:300]).lower(), f"{docname} is printed"


def _docnames(entry):
    """A chapter's page and the pages nested under it (its study page)."""
    yield entry["file"]
    for section in entry.get("sections", []):
        yield from _docnames(section)


def _cells(line):
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]


WEB_ONLY = re.compile(r"^(:{3,}|`{3,})\{only\}\s*html\s*$.*?^\1\s*$", re.M | re.S)
"""A block that only the web book shows (``{only} html``)."""


def audit_tables(cells):
    """The tables with a verdict and a finding column among a notebook's Markdown outputs
    that the printed book prints (not in an ``{only} html`` block: a reproduction table, the
    appendix's summaries), each as its list of rows; a table printed twice in one output (a web
    copy and a printed copy) counts once.

    Examples
    --------
    >>> cell = nbformat.v4.new_code_cell(outputs=[nbformat.v4.new_output(
    ...     "execute_result",
    ...     {"text/markdown": "| quantity | verdict | finding |\\n|---|---|---|\\n"
    ...                       "| T | source-error | ch1-T |"})])
    >>> list(audit_tables([cell]))
    [[{'quantity': 'T', 'verdict': 'source-error', 'finding': 'ch1-T'}]]
    """
    for cell in cells:
        for output in cell.get("outputs", []):
            text = WEB_ONLY.sub("", output.get("data", {}).get("text/markdown", ""))
            for table in dict.fromkeys(re.findall(r"(?:^\|.*\|[ \t]*$\n?)+", text, re.M)):
                lines = table.strip().splitlines()
                head = _cells(lines[0])
                if {"verdict", "finding"} <= set(head):
                    yield [dict(zip(head, _cells(line))) for line in lines[2:]]


def _parts():
    """Each page of the printed book's chapters and appendices, with the opening of its
    chapter or appendix: ``("CHAPTER", 0)`` for Chapter 1, ``("APPENDIX", 1)`` for B."""
    _, chapters, appendices, _ = _toc()
    for number, chapter in enumerate(chapters):
        for docname in _docnames(chapter):
            yield docname, ("CHAPTER", number)
    for number, docname in enumerate(appendices):
        yield docname, ("APPENDIX", number)


def _part_pages(pages, word, number):
    first = _openings(pages, word)[number]
    later = [k for k in _openings(pages, "CHAPTER") + _openings(pages, "APPENDIX") if k > first]
    return pages[first:min(later, default=len(pages))]


def verdict_counts(text):
    """How many times each verdict is printed in a squeezed text, the longer verdicts first
    (``reproduced`` is a part of ``not-reproduced``).

    Examples
    --------
    >>> counts = verdict_counts(squeeze("reproduced not-reproduced, not-reproduced"))
    >>> counts["reproduced"], counts["not-reproduced"]
    (1, 2)
    """
    counts = {}
    for verdict in sorted(VERDICTS, key=len, reverse=True):
        token = squeeze(verdict)
        counts[verdict] = text.count(token)
        text = text.replace(token, "|")
    return counts


def test_every_row_prints_its_verdict_and_finding(pages):
    """Every reproduction table (and every list of rows of the appendix) prints each of its
    rows, with its verdict and its finding, on the pages of its chapter (or appendix)."""
    checked = 0
    for docname, (word, number) in _parts():
        rows = [row for table in audit_tables(_source(docname)[0]) for row in table]
        if not rows:
            continue
        where = f"{docname} ({word.lower()} {number + 1})"
        text = squeeze("".join(_part_pages(pages, word, number)))
        for row in rows:
            assert squeeze(row["quantity"]) in text, f"{where}: no row {row['quantity']!r}"
        printed = verdict_counts(text)
        for verdict, count in Counter(r["verdict"] for r in rows).items():
            assert printed[verdict] >= count, \
                f"{where}: {count} rows are {verdict}, {printed[verdict]} printed"
        for finding, count in Counter(r["finding"] for r in rows if r["finding"]).items():
            assert text.count(squeeze(finding)) >= count, \
                f"{where}: {count} rows have the finding {finding}, fewer printed"
        checked += 1
    assert checked, "no page has a table of verdicts and findings"


def test_the_front_matter_gives_edition_licences_citation_and_sources(edition, pages):
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    front = squeeze(" ".join(pages[:4])).lower()
    said = {"CC BY 4.0": "ccby4.0", "MIT": "mitlicence",
            "the edition": "answerkey" if edition == "answer key" else "studentsedition",
            "the title": squeeze(citation["title"]).lower(),
            "the version": f"version{citation['version']}",
            "the authors": squeeze(citation["authors"][0]["name"]).lower(),
            "the citation file": "citation.cff", "the sources": "repository",
            "the web book": "makebook"}
    missing = [what for what, text in said.items() if text not in front]
    assert not missing, f"the first pages of the {edition} do not give {missing}"


HEADING = re.compile(r"^(\d+\.)+\d*\s+\S|^[A-Z]\.\d+(\.\d+)*\s+\S|^\w+: \d+ rows")
"""A heading as pdftotext prints it: a numbered section's title (``3.4 The problem``, ``A.2
Findings``), or the bold heading the appendix gives each chapter's table."""


def lonely_headings(pages):
    r"""The pages (numbered from 1) whose text between the running header (the first line) and
    the running footer (the last) is a heading alone.

    Examples
    --------
    >>> lonely_headings(["Book\n3.4 The table\n12 Chapter 3", "Book\n| a | b |\n3.4 x 13",
    ...                  "Book\n14 Chapter 3"])
    [1]
    """
    alone = []
    for k, page in enumerate(pages):
        lines = [line for line in page.strip().splitlines() if line.strip()]
        body = lines[1:-1]
        if 1 <= len(body) <= 2 and HEADING.match(body[0]):
            alone.append(k + 1)
    return alone


def test_no_page_holds_only_a_heading(pages):
    """No page holds a heading alone, with what it heads on the next page (a table, whose
    heading is kept with it)."""
    alone = lonely_headings(pages)
    assert not alone, f"pages holding only a heading: {[(k, pages[k - 1][:120]) for k in alone]}"


def _hidden_code():
    """The distinctive lines of the code of the cells that the web book hides."""
    found = []
    for notebook in sorted((ROOT / "book").glob("*.ipynb")):
        for cell in nbformat.read(notebook, as_version=4).cells:
            tags = set(cell.metadata.get("tags", []))
            if cell.cell_type == "code" and tags & {"hide-input", "remove-input"}:
                found += [(notebook.name, line.strip()) for line in cell.source.splitlines()
                          if 30 <= len(line.strip()) <= 70]
    return found


def test_no_code_the_web_book_hides_is_printed(pages):
    text = squeeze("".join(pages))
    hidden = _hidden_code()
    assert hidden, "no cell hides its code: nothing to check"
    printed = [(name, line) for name, line in hidden if squeeze(line) in text]
    assert not printed, f"{len(printed)} lines of hidden code printed: {printed[:3]}"


def solutions():
    """``{(lecture, k): lines}``: the distinctive lines of each solution's code in the
    notebooks: lines of 25 characters or more that no other cell of any notebook holds (as a part
    of a line, however spaced)."""
    cells, elsewhere = {}, []
    for notebook in sorted((ROOT / "book").glob("*.ipynb")):
        content = nbformat.read(notebook, as_version=4)
        mine = solution_code(content)
        for k, code in enumerate(mine):
            cells[notebook.stem, k] = code
        elsewhere += [cell.source for cell in content.cells if cell.source not in mine]
    others = squeeze("\n".join(elsewhere))
    return {key: [line.strip() for line in code.splitlines()
                  if len(line.strip()) >= 25 and squeeze(line) not in others]
            for key, code in cells.items()}


def test_the_students_edition_holds_no_solution(edition, pages):
    """The students' PDF prints no line of any solution's code; the answer key prints a line of
    every one of them (so the search would find one that was left)."""
    text = squeeze("".join(pages))
    found = solutions()
    assert {lecture for lecture, _ in found} >= {Path(p).name for p in lectures()}
    assert all(found.values()), [key for key, lines in found.items() if not lines]
    printed = {key: [line for line in lines if squeeze(line) in text]
               for key, lines in found.items()}
    if edition == "student":
        left = {key: lines for key, lines in printed.items() if lines}
        assert not left, f"solutions in the students' PDF: {left}"
    else:
        missing = [key for key, lines in found.items() if lines and not printed[key]]
        assert not missing, f"solutions the answer key does not print: {missing}"
