"""Every built page in a real browser: headless Chromium, from ``file://``, offline.

Each page must load with no console error and no request leaving the machine, render all its
TeX, and fit a 1280 px wide window (wide content scrolls inside its own code cell or table, not
the page). Within the page, with every dropdown and folded cell open: no display equation is
wider than its column, and on a lecture page (``lecture_pages``) no table is, nor the code of
any code cell (it would need scrolling sideways). Solution dropdowns must open, and animations
must advance when played, with their control icons drawn. A screenshot of the top of each page
is written to ``_build/screenshots`` for a reader to look at.

Runs on the HTML that ``make book`` writes (``MECHNUM_BUILT_HTML``), with Debian's Chromium
(``apt-get install chromium``; ``MECHNUM_CHROMIUM`` names another binary) driven by Playwright.
Skipped, with the reason, when either is missing.
"""

import os
import shutil
from pathlib import Path

import pytest
from lecture_pages import MAX_LINE, lectures

BUILT = os.environ.get("MECHNUM_BUILT_HTML")
CHROMIUM = os.environ.get("MECHNUM_CHROMIUM") or shutil.which("chromium")
pytestmark = [
    pytest.mark.skipif(not BUILT, reason="MECHNUM_BUILT_HTML is not set"),
    pytest.mark.skipif(not CHROMIUM, reason="Chromium is not installed (Debian: apt-get install "
                                            "chromium): the browser tests are skipped"),
]
LOCAL = ("file:", "data:", "blob:", "about:")
# Chromium's own background traffic stays off, so that any request seen comes from the page
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--no-first-run",
         "--disable-component-update", "--disable-sync", "--disable-quic"]
# TeX left in the text outside MathJax's output and outside code: a control word, a delimiter
TEX_LEFT = r"""() => {
    const skip = "SCRIPT,STYLE,PRE,CODE,TEXTAREA,MJX-CONTAINER,MJX-ASSISTIVE-MML";
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    const left = [];
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
        if (node.parentElement.closest(skip.split(",").join(","))) continue;
        if (/\\[A-Za-z]{2,}|\\[()\[\]]|\$[^$\s]|[_^]\{/.test(node.textContent))
            left.push(node.textContent.trim().slice(0, 80));
    }
    return left;
}"""


# Everything wider than the box it sits in, with the dropdowns and folded cells open: display
# equations (MathJax's containers scroll), tables (in the theme's scrolling box), code cells' input
TOO_WIDE = r"""() => {
    document.querySelectorAll("details").forEach(d => { d.open = true; });
    document.querySelectorAll(".toggle-hidden").forEach(e => e.classList.remove("toggle-hidden"));
    const tex = (m) => {
        const items = window.MathJax && MathJax.startup.document.getMathItemsWithin(m);
        return items && items.length ? items[0].math : m.textContent;
    };
    const longest = (text) => text.split("\n").reduce((a, b) => b.length > a.length ? b : a, "");
    const wider = (selector, width, box, text) => [...document.querySelectorAll(selector)]
        .filter(e => Math.round(width(e)) > box(e).clientWidth + 1)
        .map(e => ({text: text(e).replace(/\s+/g, " ").trim().slice(0, 70),
                    width: Math.round(width(e)), column: box(e).clientWidth}));
    return {
        equations: wider("article mjx-container[display='true']", e => e.scrollWidth, e => e, tex),
        tables: wider("article table", e => e.getBoundingClientRect().width, e => e.parentElement,
                      e => e.rows.length ? e.rows[0].textContent : ""),
        code: wider("article div.cell_input pre", e => e.scrollWidth, e => e,
                    e => longest(e.textContent)),
    };
}"""


def pages():
    """The book's pages: not the theme's snippets under ``_static``, nor the redirect at the top
    (``index.html`` sends the reader to ``book/index.html``, which is tested)."""
    if not BUILT:
        return []
    root = Path(BUILT).resolve()
    return sorted(p for p in root.rglob("*.html")
                  if not p.relative_to(root).parts[0].startswith("_")
                  and 'http-equiv="Refresh"' not in p.read_text(encoding="utf-8"))


def name(path):
    return str(path.relative_to(Path(BUILT).resolve()))


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield chromium
        chromium.close()


class Visit:
    """A page opened in a fresh window (1280 x 900 unless given), with its console errors and
    remote requests."""

    def __init__(self, browser, path, width=1280, height=900):
        self.context = browser.new_context(viewport={"width": width, "height": height})
        self.errors, self.remote = [], []
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.goto(path.as_uri() if isinstance(path, Path) else path, wait_until="load")
        self.page.evaluate("() => window.MathJax && MathJax.startup && MathJax.startup.promise")

    def _route(self, route):
        if route.request.url.startswith(LOCAL):
            route.continue_()
        else:  # nothing leaves the machine: record it and refuse it
            self.remote.append(route.request.url)
            route.abort()

    def close(self):
        self.context.close()


@pytest.fixture(scope="module")
def measured(browser):
    """``measured(path)``: what one visit of the page found (each page is visited once)."""
    found = {}

    def measure(path):
        if path not in found:
            visit = Visit(browser, path)
            shots = Path(BUILT).parent / "screenshots"
            shots.mkdir(exist_ok=True)
            visit.page.screenshot(path=shots / (name(path).replace("/", "_") + ".png"))
            found[path] = {"left": visit.page.evaluate(TEX_LEFT), "width": visit.page.evaluate(
                "() => [document.documentElement.scrollWidth, window.innerWidth]")}
            found[path].update(visit.page.evaluate(TOO_WIDE), errors=visit.errors,
                               remote=visit.remote)
            visit.close()
        return found[path]
    return measure


@pytest.mark.parametrize("path", pages(), ids=name)
def test_page_loads_clean_renders_its_tex_and_fits_the_window(measured, path):
    page = measured(path)
    assert not page["errors"], f"console errors: {page['errors']}"
    assert not page["remote"], f"requests leaving the machine: {page['remote']}"
    assert not page["left"], f"TeX left unrendered: {page['left'][:5]}"
    width = page["width"]
    assert width[0] <= width[1], f"the page is {width[0]} px wide in a {width[1]} px window"


def lecture_pages():
    return [path for path in pages() if name(path).removesuffix(".html") in lectures()]


@pytest.mark.parametrize("path", pages(), ids=name)
def test_display_equations_fit_their_column(measured, path):
    too_wide = measured(path)["equations"]
    assert not too_wide, f"equations wider than their column (px): {too_wide}"


@pytest.mark.parametrize("path", lecture_pages(), ids=name)
def test_lecture_tables_fit_their_column(measured, path):
    too_wide = measured(path)["tables"]
    assert not too_wide, f"tables wider than their column (px): {too_wide}"


@pytest.mark.parametrize("path", lecture_pages(), ids=name)
def test_lecture_code_cells_need_no_sideways_scrolling(measured, path):
    too_wide = measured(path)["code"]
    assert not too_wide, f"code cells wider than their column (px): {too_wide}"


def test_the_width_checks_find_what_is_too_wide(browser):
    """A wide equation, table and code cell added to a lecture page are found; the page's own
    narrow ones are not (each check fails on a broken detector)."""
    visit = Visit(browser, lecture_pages()[0])
    try:
        before = visit.page.evaluate(TOO_WIDE)
        visit.page.evaluate(r"""async () => {
            const article = document.querySelector("article");
            const add = (html) => article.insertAdjacentHTML("beforeend", html);
            add('<div class="math notranslate nohighlight">\\[' + 'x + '.repeat(150) +
                'x\\]</div>');
            add('<div class="pst-scrollable-table-container"><table><tr>' +
                '<td>column</td>'.repeat(100) + '</tr></table></div>');
            add('<div class="cell_input"><pre>' + 'y = 1; '.repeat(40) + '</pre></div>');
            await MathJax.typesetPromise();
        }""")
        after = visit.page.evaluate(TOO_WIDE)
    finally:
        visit.close()
    for kind in ("equations", "tables", "code"):
        assert len(after[kind]) == len(before[kind]) + 1, kind
        assert after[kind][-1]["width"] > after[kind][-1]["column"] + 100, after[kind][-1]


def with_selector(selector):
    """The pages whose HTML holds ``selector``'s class (read from the file, no browser)."""
    return [p for p in pages() if selector in p.read_text(encoding="utf-8")]


@pytest.mark.parametrize("path", with_selector('class="solution dropdown'), ids=name)
def test_solution_dropdowns_open(browser, path):
    visit = Visit(browser, path)
    solutions = visit.page.locator("div.solution.dropdown")
    try:
        for i in range(solutions.count()):
            body = solutions.nth(i).locator("#solution-content").first
            assert not body.is_visible(), f"solution {i} is open before a click"
            solutions.nth(i).locator("button.toggle-button").click()
            body.wait_for(state="visible", timeout=3000)
    finally:
        visit.close()


@pytest.mark.parametrize("path", with_selector('class="animation"'), ids=name)
def test_animations_play_and_draw_their_controls(browser, path):
    visit = Visit(browser, path)
    try:
        for animation in visit.page.locator("div.animation").all():
            animation.scroll_into_view_if_needed()
            icons = animation.locator("button svg")
            assert icons.count() == 9
            for i in range(icons.count()):
                box = icons.nth(i).bounding_box()
                assert box and box["width"] >= 10 and box["height"] >= 10, "an icon is not drawn"
            slider = animation.locator("input.anim-slider")
            before = slider.input_value()
            animation.locator('button[title="Play"]').click()
            visit.page.wait_for_timeout(600)
            assert slider.input_value() != before, "the animation did not advance when played"
            animation.locator('button[title="Pause"]').click()
    finally:
        visit.close()


def test_a_line_of_the_longest_length_fits_every_code_cell(browser):
    """CONTRIBUTING.md's longest line of code fits every code cell of the lecture pages, also
    those in narrower boxes (folded cells, solutions: book/_ext/code_width.py); two characters
    more do not fit the column's."""
    widths, over = set(), []
    for path in lecture_pages():
        visit = Visit(browser, path)
        try:
            fits = visit.page.evaluate("""(n) => {
                document.querySelectorAll("details").forEach(d => { d.open = true; });
                const cells = [...document.querySelectorAll("article div.cell_input pre")];
                const fit = (k) => cells.map(pre => { pre.textContent = "x".repeat(k);
                                                      return pre.scrollWidth <= pre.clientWidth; });
                const widths = cells.map(pre => pre.clientWidth);
                return {widths: widths, at: fit(n), over: fit(n + 2)};
            }""", MAX_LINE)
        finally:
            visit.close()
        assert all(fits["at"]), f"{name(path)}: a {MAX_LINE}-character line needs scrolling"
        widths.update(fits["widths"])
        over += fits["over"]
    assert len(widths) >= 2, "the lectures lack a code cell in a narrower box to measure"
    assert not all(over)


# Every slide of a deck, shown in turn: whether it is the one shown, its size and its content
# (the speaker notes left out), its images that did not load, MathJax's errors and TeX left
SLIDES = r"""async () => {
    const tex = /\\[A-Za-z]{2,}|\\[()\[\]]|\$[^$\s]|[_^]\{/;
    const frame = () => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
    if (!Reveal.isReady()) await new Promise(r => Reveal.on("ready", r));
    const found = [];
    for (const slide of Reveal.getSlides()) {
        const {h, v = 0} = Reveal.getIndices(slide);
        Reveal.slide(h, v);
        for (let k = 0; k < 30 && !slide.classList.contains("present"); k++) await frame();
        await frame();
        const shown = slide.cloneNode(true);
        shown.querySelectorAll("aside.notes, mjx-container, pre").forEach(e => e.remove());
        const box = slide.getBoundingClientRect();
        found.push({
            slide: `${h}/${v}`, present: slide.classList.contains("present"),
            width: box.width, height: slide.scrollHeight,
            text: slide.innerText.replace(/on the page/, "").trim().length,
            broken: [...slide.querySelectorAll("img")]
                .filter(i => !i.complete || i.naturalWidth === 0).map(i => i.src),
            merror: slide.querySelectorAll("mjx-merror").length,
            tex: tex.test(shown.textContent) ? shown.textContent.match(tex)[0] : null,
        });
    }
    return {slides: found, height: Reveal.getConfig().height};
}"""


def decks():
    return sorted((Path(BUILT).resolve() / "slides").glob("*.html")) if BUILT else []


@pytest.mark.parametrize("path", decks(), ids=name)
def test_every_slide_of_a_deck_renders_offline(browser, path):
    """Each slide of each lecture's deck is shown in turn at the slides' own size: it is the
    slide shown, it has content, its images loaded, its mathematics is typeset without a
    MathJax error and no TeX is left, and its content fits the slide's height; the deck logs no
    console error and requests nothing outside file://."""
    visit = Visit(browser, path, 1280, 720)
    try:
        found = visit.page.evaluate(SLIDES)
    finally:
        visit.close()
    slides = found["slides"]
    assert len(slides) >= 10, f"{len(slides)} slides"
    assert not visit.errors, f"console errors: {visit.errors}"
    assert not visit.remote, f"requests leaving file://: {visit.remote}"
    for slide in slides:
        where = f"{name(path)}#/{slide['slide']}"
        assert slide["present"] and slide["width"] > 0, f"{where} is not shown: {slide}"
        assert slide["text"] > 0, f"{where} is empty"
        assert not slide["broken"], f"{where}: images not loaded {slide['broken']}"
        assert not slide["merror"] and not slide["tex"], f"{where}: TeX {slide['tex']!r}"
        assert slide["height"] <= found["height"], \
            f"{where}: {slide['height']} px of content on a {found['height']} px slide"


def test_the_slide_checks_find_a_broken_slide(browser):
    """A slide added to a deck with a missing image, bad TeX and too much content fails every
    check that the decks pass."""
    visit = Visit(browser, decks()[0], 1280, 720)
    try:
        visit.page.evaluate(r"""() => {
            const column = document.createElement("section");
            column.innerHTML = '<section><h2>Broken</h2><img src="missing.png">' +
                '<div class="math">\\[\\frac{1}\\]</div>' +
                '<p>$x_{1}$ left</p>' + '<p>line</p>'.repeat(60) + '</section>';
            document.querySelector(".reveal .slides").appendChild(column);
            Reveal.sync();
            return MathJax.typesetPromise([column]);
        }""")
        slides = visit.page.evaluate(SLIDES)
    finally:
        visit.close()
    last, height = slides["slides"][-1], slides["height"]
    assert last["broken"] and last["merror"] and last["tex"] and last["height"] > height
    assert not any(s["broken"] or s["merror"] or s["tex"] for s in slides["slides"][:-1])


# The layout a reader needs at a width: the verdict column of every table of verdicts in view
# without scrolling; every inline formula outside a table either inside its line or scrollable
# within its own box, and not past the column; every self-check's feedback line wrapped
LAYOUT = r"""() => {
    const article = document.querySelector("article").getBoundingClientRect();
    const out = {verdicts: [], formulas: [], feedback: []};
    for (const th of document.querySelectorAll("article th")) {
        if (th.textContent.trim() !== "verdict") continue;
        const box = th.closest(".pst-scrollable-table-container")
            || th.closest("table").parentElement;
        const r = th.getBoundingClientRect(), b = box.getBoundingClientRect();
        if (r.right > b.right + 1 || r.left < b.left - 1)
            out.verdicts.push({right: Math.round(r.right), visible: Math.round(b.right)});
    }
    for (const m of document.querySelectorAll("article mjx-container:not([display='true'])")) {
        if (m.closest("table, pre")) continue;
        const r = m.getBoundingClientRect(), style = getComputedStyle(m);
        const clips = ["hidden", "clip"].includes(style.overflowX) && style.display !== "inline";
        if (r.right > article.right + 1 || (clips && m.scrollWidth > m.clientWidth + 1))
            out.formulas.push({tex: (m.getAttribute("aria-label") || m.textContent).slice(0, 50),
                               right: Math.round(r.right), column: Math.round(article.right)});
    }
    for (const pre of document.querySelectorAll("article div.cell_output pre")) {
        if (!/^Exercise \d+\.\d+:/.test(pre.textContent)) continue;
        if (pre.scrollWidth > pre.clientWidth + 1)
            out.feedback.push({text: pre.textContent.slice(0, 50), width: pre.scrollWidth,
                               column: pre.clientWidth});
    }
    return out;
}"""
WIDTHS = (1280, 390)
"""A desktop's window and a phone's (390 CSS px, a current phone held upright)."""


def layout_pages():
    """The lecture and study pages and the appendix of the book, and the lecture pages of the
    student edition (whose check cells print "not yet") when it is built."""
    found = [p for p in pages() if name(p).startswith("book/0") or "published_values" in name(p)]
    student = os.environ.get("MECHNUM_STUDENT_HTML")
    if student:
        found += [Path(student).resolve() / f"{lecture}.html" for lecture in lectures()]
    return found


def layout_id(path):
    student = os.environ.get("MECHNUM_STUDENT_HTML")
    if student and path.is_relative_to(Path(student).resolve()):
        return "student/" + str(path.relative_to(Path(student).resolve()))
    return name(path)


@pytest.fixture(scope="module")
def layout(browser):
    """``layout(path, width)``: what :data:`LAYOUT` finds on the page in a window that wide."""
    found = {}

    def measure(path, width):
        if (path, width) not in found:
            visit = Visit(browser, path, width, 900)
            try:
                visit.page.wait_for_timeout(100)   # web_layout.js marks after MathJax
                found[path, width] = visit.page.evaluate(LAYOUT)
            finally:
                visit.close()
        return found[path, width]
    return measure


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("path", layout_pages(), ids=layout_id)
def test_the_verdict_column_is_in_view(layout, path, width):
    hidden = layout(path, width)["verdicts"]
    assert not hidden, f"at {width} px the verdict column needs scrolling to: {hidden}"


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("path", layout_pages(), ids=layout_id)
def test_long_inline_formulas_wrap_or_scroll(layout, path, width):
    cut = layout(path, width)["formulas"]
    assert not cut, f"at {width} px inline formulas are cut off: {cut[:3]}"


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("path", layout_pages(), ids=layout_id)
def test_the_feedback_of_a_self_check_wraps(layout, path, width):
    cut = layout(path, width)["feedback"]
    assert not cut, f"at {width} px a feedback line is cut off: {cut}"
