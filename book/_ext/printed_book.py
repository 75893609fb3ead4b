"""The printed book (``make pdf``): its parts and its tables, for Sphinx's LaTeX builder.

The web book and the PDF are built from the same pages; this extension changes only the PDF:

* **the preface**: the root page's own text is printed as an unnumbered chapter, *Preface*
  (``latex_preface_title``), before Chapter 1, with its sections unnumbered; Sphinx alone drops
  it, or makes each of its sections a chapter;
* **the appendices**: the pages of the table of contents' unnumbered parts that follow a
  numbered part are printed after LaTeX's ``\\appendix``, lettered A, B, ...;
* **pages left out** (``latex_exclude_docs``, the API reference: the web book keeps it); a
  cross-reference to such a page prints as plain text;
* **every table fits the text width with all its columns**: a table that sets no column widths
  of its own (no ``tabularcolumns``, no ``:widths:``) gets wrapping columns whose widths follow
  its content, as browsers lay out tables (each column at least as wide as its longest
  unbreakable word, the rest of the line shared in proportion to how much longer its longest
  cell is), in ``\\small`` type, or ``\\footnotesize`` from :data:`MANY_COLUMNS` columns on;
  it may run over several pages (a ``longtable``, unless it sits in a box such as an
  admonition), and one whose words do not fit an upright line is printed on turned pages;
  a heading right before a table (its section's title, a bold paragraph) stays on its page;
* **display formulas fit the line**: one wider than the line is scaled down to its width;
* **a first page about the edition** after the title page: which edition it is
  (``printed_edition``: the answer key, or the students' edition), its licences, how to cite it
  (read from ``CITATION.cff``) and where the book and its sources live;
* **no build code**: a cell tagged ``hide-input`` or ``remove-input`` (code that builds a table
  or a figure, folded on the web) prints its output only.
"""

import re
import subprocess
from pathlib import Path

import yaml
from docutils import nodes
from sphinx import addnodes
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.writers.latex import LaTeXTranslator

MANY_COLUMNS = 6
"""Tables with this many columns or more are set in ``\\footnotesize`` type, others in
``\\small``."""
LINE_PT = {"portrait": 450.0, "landscape": 640.0}
"""The text width in points that Sphinx's LaTeX gives the narrower of the two papers, A4 or US
Letter, less two 1 in margins: upright (A4), and turned (US Letter's 11 in)."""
COLUMN_PADDING_PT = 12.0
"""What each column spends on its padding (two ``\\tabcolsep`` of 6 pt)."""
CHAR_WIDTH_EM = 0.55
"""The width of a character of text, in ems of its font: FreeSerif's digits are 0.5 em, its
lower case a little less on average, its capitals more; with this margin a column fits its
longest word."""
FONT_PT = {r"\small": 9.0, r"\footnotesize": 8.0}
"""The sizes of the tables' type at the book's 10 pt."""

PREAMBLE = r"""
% printed_book: the table of contents is "Contents" (Sphinx names it after the first part)
\addto\captionsenglish{\renewcommand{\contentsname}{Contents}}
% table columns of given widths (Sphinx's \X) set ragged right: a narrow justified column
% opens wide gaps between its words
\usepackage{ragged2e}
% a table continued from the previous page says so without a number: the book's tables have
% none (Sphinx would print "Table 1.1" there, in an appendix too)
\protected\def\sphinxtablecontinued#1{\textsf{\printedbookcontinued#1\printedbookend}}
\def\printedbookcontinued#1#2\printedbookend{%
  \ifx#1\tablename (continued from the previous page)\else#1#2\fi}
% the widest tables print on pages turned a quarter (the PDF shows them turned to read)
\usepackage{pdflscape}
\makeatletter
\newcolumntype{\X}[2]{>{\RaggedRight\arraybackslash}p{\dimexpr
  (\linewidth-\spx@arrayrulewidth)*#1/#2-\tw@\tabcolsep-\spx@arrayrulewidth\relax}}
\makeatother
% a display formula wider than the line is scaled down to its width
\newsavebox\printedbookdisplay
\newcommand*\fitdisplay[1]{%
  \sbox\printedbookdisplay{$\displaystyle #1$}%
  \ifdim\wd\printedbookdisplay>\linewidth
    \resizebox{\linewidth}{!}{\usebox\printedbookdisplay}%
  \else\usebox\printedbookdisplay\fi}
"""


def _latex(text):
    return nodes.raw("", text, format="latex")


def unbreakable(text):
    """The longest piece of a cell's text that a line cannot break: a word, or the part of a
    hyphenated word between two hyphens (a line may break after a hyphen, not after a minus).

    Examples
    --------
    >>> unbreakable("within-input-rounding in Sec. 4"), unbreakable("x = -0.0996725")
    ('rounding', '-0.0996725')
    """
    pieces = re.split(r"\s+|(?<=\w)-(?=\w)", text)
    return max(pieces, key=len)


def least_widths(cells):
    """The least width, in characters, of each column of a table: its longest unbreakable piece
    (:func:`unbreakable`), at least 1.

    ``cells`` lists the rows, each a list of the texts of its cells.

    Examples
    --------
    >>> least_widths([["where", "verdict"], ["Sec. 4", "reproduced-after-correction"]])
    [5, 10]
    """
    return [max(1, max(len(unbreakable(text)) for text in column)) for column in zip(*cells)]


def column_widths(cells, available):
    """The widths, in characters, of a table's columns on a line of ``available`` characters.

    A column is at least as wide as its longest unbreakable piece (:func:`least_widths`) and at
    most as wide as its longest text; when all longest texts do not fit on the line, every
    column gets its least width and a share of the rest of the line in proportion to what it
    lacks (the automatic table layout of HTML).

    Examples
    --------
    >>> column_widths([["a", "b b"], ["cc", "ddd ddd ddd"]], available=40)
    [2, 11]
    >>> column_widths([["word", "some words that wrap"], ["x", "more"]], available=14)
    [4, 10]
    """
    longest = [max(len(text) for text in column) for column in zip(*cells)]
    least = least_widths(cells)
    if sum(longest) <= available:
        return longest
    lack = [most - low for most, low in zip(longest, least)]
    spare = max(0, available - sum(least))
    return [low + round(spare * gap / sum(lack)) if sum(lack) else low
            for low, gap in zip(least, lack)]


def layout(cells, pages=tuple(LINE_PT)):
    """How a table prints: its type size, its page (the first of ``pages`` whose line its least
    widths fit: ``"portrait"``, else ``"landscape"``), and its column widths in points, padding
    included.

    Examples
    --------
    >>> layout([["where", "verdict"], ["Sec. 4", "reproduced"]])
    ('\\\\small', 'portrait', [41.7, 61.5])
    """
    size = r"\footnotesize" if len(cells[0]) >= MANY_COLUMNS else r"\small"
    char_pt = CHAR_WIDTH_EM * FONT_PT[size]
    for page in pages:
        available = (LINE_PT[page] - COLUMN_PADDING_PT * len(cells[0])) / char_pt
        if sum(least_widths(cells)) <= available:
            break
    widths = column_widths(cells, int(available))
    return size, page, [round(w * char_pt + COLUMN_PADDING_PT, 1) for w in widths]


def _cell_texts(table):
    rows = [[" ".join(entry.astext().split()) for entry in row.children
             if isinstance(entry, nodes.entry)] for row in table.findall(nodes.row)]
    width = max((len(row) for row in rows), default=0)
    # a spanned cell leaves its row short: the missing cells are empty
    return [row + [""] * (width - len(row)) for row in rows]


def _heading_before(table):
    """The heading right before a table: its section's title, or a paragraph of bold text
    alone (as the appendix heads each chapter's table); None if something else comes first."""
    previous = table.previous_sibling() if table.parent is not None else None
    if isinstance(previous, nodes.title):
        return previous
    if isinstance(previous, nodes.paragraph) and previous.children and all(
            isinstance(child, nodes.strong) for child in previous.children):
        return previous
    return None


BOXES = (nodes.Admonition, nodes.sidebar, nodes.topic, nodes.footnote, nodes.table)
"""The nodes that LaTeX sets in a box, where a table can neither break across pages nor turn."""


def _ancestors(node):
    while node.parent is not None:
        node = node.parent
        yield node


class PrintedTables(SphinxPostTransform):
    """Give every table without column widths of its own wrapping columns that fit the line,
    and smaller type."""

    default_priority = 400
    formats = ("latex",)

    def apply(self, **kwargs):
        for table in list(self.document.findall(nodes.table)):
            if table.get("printed_book") or self._has_own_widths(table):
                continue
            tgroup = next(table.findall(nodes.tgroup))
            colspecs = [c for c in tgroup.children if isinstance(c, nodes.colspec)]
            cells = _cell_texts(table)
            if not cells or len(cells[0]) != len(colspecs):
                continue
            boxed = any(isinstance(a, BOXES) for a in _ancestors(table))
            size, page, widths = layout(cells, ("portrait",) if boxed else tuple(LINE_PT))
            for colspec, width in zip(colspecs, widths):
                # LaTeX shares the line among the columns in proportion to these numbers
                # (tenths of a point), then takes each column's padding out of its share
                colspec["colwidth"] = round(10 * width)
            table["classes"] = [c for c in table["classes"] if c != "colwidths-auto"]
            table["classes"].append("colwidths-given")
            if not boxed:
                table["classes"].append("longtable")    # it may run over several pages
            table["printed_book"] = True
            turn = page == "landscape"
            parent = table.parent
            index = parent.index(table)
            heading = _heading_before(table)
            parent.insert(index + 1, _latex("\\endgroup" + "\\end{landscape}" * turn + "\n"))
            if turn and isinstance(heading, nodes.paragraph):
                # the heading turns with its table (a turned table starts a page)
                parent.insert(parent.index(heading), _latex("\\begin{landscape}\n"))
                parent.insert(index + 1, _latex("\\begingroup" + size + "\n"))
            else:
                # no page break between a heading and its table
                keep = "\\nopagebreak" if heading is not None and not turn else ""
                parent.insert(index, _latex("\\begin{landscape}" * turn + keep + "\\begingroup"
                                            + size + "\n"))

    @staticmethod
    def _has_own_widths(table):
        if "colwidths-given" in table["classes"]:
            return True
        previous = table.previous_sibling() if table.parent is not None else None
        return isinstance(previous, addnodes.tabular_col_spec)


class PrintedParts(SphinxPostTransform):
    """The preface, the appendices and the pages left out, on the book's assembled tree."""

    default_priority = 5          # before the cross-references are resolved (10)
    formats = ("latex",)

    def apply(self, **kwargs):
        root = self.config.root_doc
        if self.document.get("docname") != root or not any(
                self.document.findall(addnodes.start_of_file)):
            return                # not the whole book, or not a book of several pages
        appendices = self._appendices(root)
        for start in list(self.document.findall(addnodes.start_of_file)):
            if start["docname"] in self.config.latex_exclude_docs:
                start.parent.remove(start)
                self.app.builder.docnames.discard(start["docname"])
        starts = [s for s in self.document.findall(addnodes.start_of_file)
                  if s["docname"] in appendices]
        if starts:
            starts[0].parent.insert(starts[0].parent.index(starts[0]), _latex("\n\\appendix\n"))
        self._preface()

    def _appendices(self, root):
        """The pages of the unnumbered toctrees of the root page that follow a numbered one."""
        found, numbered = set(), False
        for toctree in self.env.get_doctree(root).findall(addnodes.toctree):
            numbered = numbered or bool(toctree.get("numbered"))
            if numbered and not toctree.get("numbered"):
                found.update(toctree["includefiles"])
        return found

    def _preface(self):
        """Move the root page's text into an unnumbered chapter before the first page."""
        top = next(self.document.findall(nodes.section))
        title = self.config.latex_preface_title
        preface = nodes.section("", nodes.title(title, title), ids=["printed-book-preface"])
        text = [child for child in top.children[1:]
                if not any(child.findall(addnodes.start_of_file))]
        if not text:
            return
        for child in text:
            top.remove(child)
            preface += child
        top.insert(1, _latex("\\edef\\printedbooksecnumdepth{\\the\\value{secnumdepth}}"
                             "\\setcounter{secnumdepth}{-1}\n"))
        top.insert(2, preface)
        top.insert(3, _latex("\\setcounter{secnumdepth}{\\printedbooksecnumdepth}\n"))


def visit_math_block(self, node):
    """A display formula in a box no wider than the line (Sphinx's own, with ``split``, runs
    into the margin); a formula marked ``nowrap`` is left as Sphinx writes it."""
    if node.get("nowrap"):
        return LaTeXTranslator.visit_math_block(self, node)
    label = f"equation:{node['docname']}:{node['label']}" if node.get("label") else None
    parts = [part.strip() for part in node.astext().split("\n\n") if part.strip()]
    environment = "equation" if label or self.config.math_number_all else "equation*"
    self.body.append(f"\\begin{{{environment}}}" + (f"\\label{{{label}}}" if label else "")
                     + "\n\\fitdisplay{\\begin{aligned}" + "\\\\\n".join(parts)
                     + f"\\end{{aligned}}}}\n\\end{{{environment}}}")
    raise nodes.SkipNode


class NoBuildCode(SphinxPostTransform):
    """Drop the code of the cells whose code the web book folds or hides (``hide-input``,
    ``remove-input``): what prints is their output."""

    default_priority = 400
    formats = ("latex",)

    def apply(self, **kwargs):
        for cell in list(self.document.findall(nodes.container)):
            tags = set(cell.get("classes", []))
            if cell.get("nb_element") == "cell_code" and tags & {"tag_hide-input",
                                                                 "tag_remove-input"}:
                for part in [c for c in cell.children if isinstance(c, nodes.container)
                             and c.get("nb_element") == "cell_code_source"]:
                    cell.remove(part)


def tex_escape(text):
    """Text set as it is in LaTeX.

    Examples
    --------
    >>> print(tex_escape("MIT & CC-BY-4.0, 100 % {x}_1"))
    MIT \\& CC-BY-4.0, 100 \\% \\{x\\}\\_1
    """
    return re.sub(r"([&%$#_{}])", r"\\\1", str(text)).replace("~", r"\textasciitilde{}")


def _commit(folder):
    try:
        found = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=folder,
                               capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return found.stdout.strip() if found.returncode == 0 else None


def front_matter(citation, edition, commit):
    """The LaTeX of the page after the title page: the edition, the licences, the citation and
    where the book and its sources live, from ``CITATION.cff``'s fields."""
    authors = ", ".join(a.get("name") or " ".join(filter(None, (a.get("given-names"),
                                                               a.get("family-names"))))
                        for a in citation.get("authors", []))
    year = str(citation.get("date-released", ""))[:4]
    title, version = citation.get("title", ""), citation.get("version", "")
    where = [f"the sources: \\url{{{citation[key]}}}" for key in ("repository-code",)
             if citation.get(key)]
    where += [f"the book: \\url{{{citation[key]}}}" for key in ("url",) if citation.get(key)]
    built = f" (commit \\texttt{{{tex_escape(commit)}}})" if commit else ""
    where.append("the web book, with every chapter as a notebook, the package's wheel and the "
                 "lectures' slides, is built from the same repository as this PDF" + built
                 + " by \\texttt{make book}; its page \\emph{Run the chapters yourself} serves "
                 "the chapters and the package")
    return "\n".join([
        r"\clearpage\thispagestyle{empty}\begingroup\small\setlength{\parskip}{0.6em}",
        r"\section*{About this book}",
        f"\\textbf{{{tex_escape(title)}}}, version {tex_escape(version)}"
        f" ({tex_escape(citation.get('date-released', ''))}), by {tex_escape(authors)}.",
        "",
        f"\\textbf{{This edition}}: {tex_escape(edition)}.",
        "",
        r"\textbf{Licences}: the text, figures and tables are licensed under the Creative "
        r"Commons Attribution 4.0 International licence (CC BY 4.0, "
        r"\url{https://creativecommons.org/licenses/by/4.0/}); the code (the package "
        r"\texttt{mechnum}, the tests and the code cells) under the MIT licence. The files "
        r"\texttt{LICENSE-TEXT.md} and \texttt{LICENSE} of the sources hold them; the studies "
        r"the chapters discuss are not covered by them.",
        "",
        f"\\textbf{{How to cite it}} (\\texttt{{CITATION.cff}}): {tex_escape(authors)} "
        f"({tex_escape(year)}). \\emph{{{tex_escape(title)}}}, version {tex_escape(version)}.",
        "",
        r"\textbf{Where it lives}: " + "; ".join(where) + ".",
        r"\endgroup\clearpage", ""])


def _add_preamble(app, config):
    elements = dict(config.latex_elements)
    elements["preamble"] = elements.get("preamble", "") + PREAMBLE
    citation_file = Path(app.srcdir) / "CITATION.cff"
    citation = (yaml.safe_load(citation_file.read_text(encoding="utf-8"))
                if citation_file.is_file() else {})
    elements["maketitle"] = (elements.get("maketitle", r"\sphinxmaketitle") + "\n"
                             + front_matter(citation, config.printed_edition,
                                            _commit(app.srcdir)))
    config.latex_elements = elements


def setup(app):
    app.add_config_value("latex_exclude_docs", [], "", [list])
    app.add_config_value("latex_preface_title", "Preface", "", [str])
    app.add_config_value("printed_edition", "the answer key, the whole book with every solution "
                         "after its exercise", "", [str])
    app.add_post_transform(PrintedParts)
    app.add_post_transform(PrintedTables)
    app.add_post_transform(NoBuildCode)
    app.add_node(nodes.math_block, override=True, latex=(visit_math_block, None))
    app.connect("config-inited", _add_preamble)
    return {"parallel_read_safe": True}
