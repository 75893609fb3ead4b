"""Every lecture page keeps the lecture's budget (issue 20; CONTRIBUTING.md, "The lecture's
budget"): at most 3,000 words of prose and 250 lines of code, every line of code at most 76
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
    read_markdown,
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
    assert counted["words"] <= MAX_WORDS, f"{counted['words']} words of prose"
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
Prose with `inline code`, maths $x_k^2 + 1$, a {doc}`reference <page>` and a
[link text](https://example.org/a/b) counts: eleven.

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
not_prose = "but a shown line of code"
```
\\begin{align}
a &= b
\\end{align}
````
<!-- a comment -->
"""


def test_words_are_prose_without_code_maths_options_or_targets():
    words, code = read_markdown(MARKDOWN)
    assert words == 5 + 11 + 3 + 1  # the heading, the paragraph, the exercise, its title
    assert code == ['not_prose = "but a shown line of code"']
    assert count_words("a $5 sum $ and - | 3,000 e.g. ok") == 7


def test_the_budget_counts_code_cells_and_finds_long_lines(monkeypatch):
    import nbformat

    cells = [nbformat.v4.new_markdown_cell("Two words."),
             nbformat.v4.new_code_cell("x = 1\n\n# a comment\n" + "y" * (MAX_LINE + 1))]
    monkeypatch.setattr("lecture_pages.notebook",
                        lambda page: nbformat.v4.new_notebook(cells=cells))
    assert budget("any") == {"words": 2, "code lines": 3, "long lines": ["y" * (MAX_LINE + 1)]}
