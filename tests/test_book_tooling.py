"""The book's own build tools (``book/_ext``) on small pages, without building the book: the
slides cut from a lecture page, the plan of the term read from a lecture notebook, the printed
book's first page, and the examples of their docstrings. ``make html-check`` and ``make pdf``
test what they build on the real book."""

import doctest
import json
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "book" / "_ext"))

import instructors  # noqa: E402
import printed_book  # noqa: E402
import slides  # noqa: E402
import web_layout  # noqa: E402

PAGE = """<html><head>
<script defer="defer" src="../_static/mathjax/tex-chtml.js"></script></head><body>
<article class="bd-article"><section id="top">
<h1><span class="section-number">3. </span>The elastica<a class="headerlink" href="#top">#</a></h1>
<p>An introduction the lecturer says.</p>
<ol><li><p>take one step of RK4;</p></li><li><p>shoot.</p></li></ol>
<section id="problem"><h2>3.1. The problem</h2>
<p>Prose before the equation.</p>
<div class="math notranslate nohighlight">\\[x' = \\cos\\theta\\]</div>
<div class="cell docutils container"><div class="cell_input"><pre>plot()</pre></div>
<div class="cell_output"><figure id="fig-1"><img src="../_images/a.png"/>
<figcaption>Fig. 3.1 A rod.</figcaption></figure></div></div>
<p>See <a href="03_elastica_study.html">the study page</a> and <a href="#fig-1">the figure</a>.</p>
</section>
<section id="talk"><h2>3.2. Only words</h2><p>First sentence here. Second one.</p></section>
<section id="exercises"><h2>3.3. Exercises</h2>
<div class="exercise admonition"><p class="admonition-title">Exercise 3.1</p>
<section id="exercise-content"><p>Write rk4_step.</p></section></div>
<div class="cell docutils container">
<div class="cell_input"><pre>def rk4_step(): ...</pre></div></div>
<div class="solution dropdown admonition"><p>SECRET-SOLUTION</p></div>
<div class="cell docutils container">
<div class="cell_input"><pre>exercises.check("3.1", rk4_step)</pre></div></div>
</section></section></article></body></html>"""


@pytest.fixture(scope="module")
def deck():
    return slides.make_deck(PAGE, "book/03_elastica", "3")


def _slides(deck):
    """The deck's slides (the innermost sections) as their HTML."""
    return re.findall(r"<section>\n<h2>.*?</section>", deck, re.S)


def test_a_deck_has_a_title_slide_and_a_column_per_section(deck):
    assert 'class="deck-title"' in deck and "Lecture 3 of" in deck
    titles = [re.sub(r"<[^>]+>", "", re.search(r"<h2>(.*?)<a", s).group(1)) for s in _slides(deck)]
    assert titles == ["3. The elastica", "3.1. The problem", "3.1. The problem",
                      "3.2. Only words", "3.3. Exercises"]


def test_a_slide_shows_what_a_lecturer_projects_and_the_prose_goes_to_the_notes(deck):
    intro, equation, figure, words, exercise = _slides(deck)
    assert "<ol" in intro and "An introduction" in intro.split('<aside class="notes">')[1]
    assert "\\cos\\theta" in equation and "Prose before" in equation.split("<aside")[1]
    assert "<figure" in figure and "plot()" not in figure
    assert '<p class="lead">First sentence here.</p>' in words
    assert "Write rk4_step." in exercise and "<section" not in exercise.split("<h2>", 1)[1]


def test_a_deck_leaves_out_the_solutions_starters_and_checks(deck):
    assert "SECRET-SOLUTION" not in deck
    assert "def rk4_step" not in deck and "exercises.check" not in deck


def test_a_decks_links_and_images_point_into_the_book(deck):
    assert 'src="../_images/a.png"' in deck
    assert 'href="../book/03_elastica_study.html"' in deck
    assert 'href="../book/03_elastica.html#fig-1"' in deck
    assert 'src="../_static/mathjax/tex-chtml.js"' in deck
    assert 'src="revealjs/reveal.js"' in deck and "headerlink" not in deck


def test_the_term_plan_reads_a_lectures_exercises(tmp_path):
    cells = [{"cell_type": "markdown", "metadata": {}, "source":
              "```{exercise}\n:label: ch2-ex-sor\nWrite it.\n```\n"},
             {"cell_type": "code", "metadata": {"mechnum": {"exercise": "2.1", "role": "check"}},
              "source": 'exercises.check("2.1", one_sor_sweep)', "outputs": []},
             {"cell_type": "markdown", "metadata": {}, "source":
              "````{exercise}\n:label: ch2-ex-why\n:class: x\nWhy?\n````"}]
    notebook = tmp_path / "02.ipynb"
    notebook.write_text(json.dumps({"cells": cells}), encoding="utf-8")
    assert instructors.exercises(notebook, 2) == [("2.1", "ch2-ex-sor", "one_sor_sweep"),
                                                  ("2.2", "ch2-ex-why", None)]


def test_the_printed_books_first_page():
    citation = {"title": "Numerical Methods & More", "version": "0.1.0",
                "date-released": "2026-12-01", "authors": [{"name": "The team"}],
                "repository-code": "https://example.org/book"}
    page = printed_book.front_matter(citation, "the students' edition", "abc123")
    assert r"Numerical Methods \& More" in page and "the students' edition" in page
    assert "CC BY 4.0" in page and "MIT licence" in page and "CITATION.cff" in page
    assert r"\url{https://example.org/book}" in page and "abc123" in page
    assert "repository" in printed_book.front_matter({}, "x", None)


@pytest.mark.parametrize("module", [slides, web_layout, printed_book, instructors])
def test_the_examples_of_the_docstrings(module):
    failed, tried = doctest.testmod(module)
    assert not failed, f"{failed} of {tried} examples fail in {module.__name__}"
