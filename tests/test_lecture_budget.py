"""Every lecture page keeps the lecture's budget (issues 20 and 31; CONTRIBUTING.md, "The
lecture's budget"): at most 3,000 words, every word of its Markdown cells with their
mathematics, and 250 non-blank lines of code, every line of code at most 76
characters (on its study page too), and, where its execution was measured, at most 30 s.

The execution time is the one strict nbval or the book build measured (``_build/execution``,
written by ``make notebooks`` and ``make book``) for the notebook as it is now; ``make test``
runs this module again after strict nbval, so there it is always measured (the preface promises
it).
"""

import sys

import pytest
from lecture_pages import (
    MAX_CODE_LINES,
    MAX_LINE,
    MAX_SECONDS,
    MAX_WORDS,
    ROOT,
    budget,
    chapter_pages,
    count_words,
    lectures,
    shown_code,
)

sys.path.insert(0, str(ROOT / "book" / "_ext"))
from execution_statistics import measured  # noqa: E402

LECTURES = list(lectures())


def test_the_table_of_contents_has_the_seven_chapters():
    assert [page[:7] for page in LECTURES] == [f"book/0{n}" for n in range(1, 8)]


@pytest.mark.parametrize("lecture", LECTURES)
def test_every_lecture_has_its_study_page_nested_under_it(lecture):
    study = f"{lecture}_study"
    assert lectures()[lecture] == [study], f"_toc.yml nests {lectures()[lecture]}, not {study}"
    assert (ROOT / f"{study}.ipynb").exists()


@pytest.mark.parametrize("lecture", LECTURES)
def test_lecture_prose_and_code_are_within_the_budget(lecture):
    counted = budget(lecture)
    assert counted["words"] <= MAX_WORDS, f"{counted['words']} words, mathematics included"
    assert counted["code lines"] <= MAX_CODE_LINES, f"{counted['code lines']} lines of code"


@pytest.mark.parametrize("page", chapter_pages())
def test_every_line_of_code_fits_the_column(page):
    long = budget(page)["long lines"]
    assert not long, f"{len(long)} lines longer than {MAX_LINE} characters: {long[:3]}"


def test_the_appendix_code_fits_the_column():
    assert not budget("book/published_values")["long lines"]


@pytest.mark.parametrize("lecture", LECTURES)  # today's chapters keep it: no switch
def test_lecture_executes_within_the_budget(lecture):
    runs = measured(ROOT, f"{lecture}.ipynb")
    if not runs:
        pytest.skip(f"{lecture} was not executed as it is now (make notebooks measures it)")
    cpu = min(record["cpu"] for _, record in runs)
    assert cpu <= MAX_SECONDS, f"{cpu:.1f} s of CPU time at best: {runs}"


MARKDOWN = """# A title of five words
(target)=
Prose with `inline code`, maths $x_k^2 + 1$ and a [link](https://example.org/a).

$$
x = y + z
$$

```{exercise}
:label: ch1-ex-1

Three more words.
```

````{admonition} Errata
:class: dropdown
```python
shown = "a line of code"
```
```{math}
a = b
```
````
<!-- a comment -->
"""


def test_every_word_counts_mathematics_included():
    # the heading (its # too), the target, the paragraph ($x_k^2 + 1$ is three words), the
    # display maths with its fences, the exercise (fences, option, body), the admonition
    # (its code and maths too), the comment
    assert count_words(MARKDOWN) == 6 + 1 + 11 + 7 + 7 + 18 + 4
    assert count_words("$$\\sum_{k=0}^n c_k t^k = 0$$") == 5  # $$\\sum_{k=0}^n, c_k, t^k, =, 0$$
    assert shown_code(MARKDOWN) == ['shown = "a line of code"']


def test_the_budget_counts_code_cells_and_finds_long_lines(monkeypatch):
    import nbformat

    cells = [nbformat.v4.new_markdown_cell("Two words, $a + b$."),
             nbformat.v4.new_code_cell("x = 1\n\n# a comment\n" + "y" * (MAX_LINE + 1))]
    monkeypatch.setattr("lecture_pages.notebook",
                        lambda page: nbformat.v4.new_notebook(cells=cells))
    assert budget("any") == {"words": 5, "code lines": 3, "long lines": ["y" * (MAX_LINE + 1)]}


def test_a_page_over_the_budget_fails(monkeypatch):
    """The budget test itself fails a lecture of 3,001 words, most of them mathematics, or of
    251 lines of code."""
    import nbformat

    for cells in ([nbformat.v4.new_markdown_cell("One formula:\n$$\n" + "x + " * 1499 + "\n$$")],
                  [nbformat.v4.new_code_cell("x = 1\n" * (MAX_CODE_LINES + 1))]):
        monkeypatch.setattr("lecture_pages.notebook",
                            lambda page, cells=cells: nbformat.v4.new_notebook(cells=cells))
        with pytest.raises(AssertionError, match="words|lines of code"):
            test_lecture_prose_and_code_are_within_the_budget("any")
