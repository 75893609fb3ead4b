"""Every figure of the chapters is readable in the web book: text of 8 px or more at 1280 px.

The committed PNG outputs are drawn at matplotlib's 100 dpi and shown at their natural size, or
scaled down to the page's content column (690 px wide in a 1280 px window; see the browser
test's screenshots). A font of ``p`` points is then ``p / 72 * 100 * scale`` pixels high. The
smallest font of a figure is the smallest ``fontsize=`` its cell sets, or the default: the
book's style file's smallest size where the chapter applies it
(``mechnum.plotting.use_book_style``), matplotlib's otherwise (10 pt for labels, ticks and
legends).
"""

import base64
import re
import struct
from pathlib import Path

import nbformat
import pytest

from mechnum.plotting import STYLE

BOOK = Path(__file__).resolve().parents[1] / "book"
COLUMN_PX, DPI, DEFAULT_PT, MIN_PX = 690, 100, 10.0, 8.0
NAMED = {"xx-small": 5.79, "x-small": 6.94, "small": 8.33, "medium": 10.0}
# the sizes the book's style file sets: the smallest is the default of a chapter that uses it
STYLE_PT = min(float(line.split(":")[1]) for line in STYLE.read_text().splitlines()
               if line.split(":")[0].strip().endswith(("size", "fontsize")))
FONTSIZE = re.compile(r"""fontsize\s*=\s*(?:([0-9.]+)|["']([a-z-]+)["'])""")


def figures():
    """``(source, width in px, default pt)`` of every PNG output of the chapters."""
    found = []
    for path in sorted(BOOK.glob("0*.ipynb")):
        notebook = nbformat.read(path, as_version=4)
        styled = any("use_book_style()" in cell.source for cell in notebook.cells
                     if cell.cell_type == "code")
        default = STYLE_PT if styled else DEFAULT_PT
        for i, cell in enumerate(notebook.cells):
            for output in cell.get("outputs", []) if cell.cell_type == "code" else []:
                png = output.get("data", {}).get("image/png")
                if png:
                    width = struct.unpack(">I", base64.b64decode(png)[16:20])[0]
                    found.append(pytest.param(cell.source, width, default,
                                              id=f"{path.stem}-cell{i}"))
    return found


def smallest_font(source, default=DEFAULT_PT):
    sizes = [float(n) if n else NAMED.get(name, default)
             for n, name in FONTSIZE.findall(source)]
    return min(sizes + [default])


def test_the_chapters_have_figures():
    assert len(figures()) >= 30


@pytest.mark.parametrize("source, width, default", figures())
def test_figure_text_is_at_least_8_px(source, width, default):
    scale = min(1.0, COLUMN_PX / width)
    pixels = smallest_font(source, default) / 72 * DPI * scale
    assert pixels >= MIN_PX, f"{pixels:.1f} px text in a {width} px wide figure"


def test_small_fonts_in_wide_figures_fail():
    assert smallest_font('ax.legend(fontsize="x-small")') == NAMED["x-small"]
    assert smallest_font("ax.legend()", STYLE_PT) == STYLE_PT == 9.0  # the style's legend
    assert smallest_font("ax.set_title('t', fontsize=5)") == 5.0
    assert 5.0 / 72 * DPI * min(1.0, COLUMN_PX / 800) < MIN_PX
