"""The rules added to scripts/check_book.py for issue 29, each caught on a synthetic bad page and
passed by a good one: numbered chapter figures, no image twice, no placeholder in a table,
complete API pages, no figure shrunk below 0.8 of its width, no clipped code block."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check_book.py"
_spec = importlib.util.spec_from_file_location("check_book_rules_under_test", SCRIPT)
check_book = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("check_book_rules_under_test", check_book)
_spec.loader.exec_module(check_book)

CHROMIUM = "/usr/bin/chromium" if Path("/usr/bin/chromium").is_file() else shutil.which("chromium")
CHROMEDRIVER = shutil.which("chromedriver") or (
    "/usr/bin/chromedriver" if Path("/usr/bin/chromedriver").is_file() else None)
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="needs Chromium (apt-get)")
needs_driver = pytest.mark.skipif(CHROMIUM is None or CHROMEDRIVER is None,
                                  reason="needs chromium and chromium-driver (apt-get)")

# a 2 x 1 PNG (any valid image will do for the static rules)
PNG = (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00"
       b"\x00\x1f\x15\xc4\x89\x00\x00\x00\rIDATx\x9cc\xf8\x0f\x00\x00\x01\x01\x00\x05\x18\xd8N"
       b"\x00\x00\x00\x00IEND\xaeB`\x82")

CHAPTER_BAD = """<!DOCTYPE html><html><body><article class="bd-article">
<p>A cell that drew a plot without a caption:</p><img src="a.png">
<figure id="fig-unnumbered"><img src="b.png"><figcaption><p>No number.</p></figcaption></figure>
<figure id="fig-ok"><img src="c.png"><figcaption><p><span class="caption-number">Fig. 1 </span>
Paper figure 9.</p></figcaption></figure>
<figure id="fig-again"><img src="c.png"><figcaption><p><span class="caption-number">Fig. 2
</span>The same image again.</p></figcaption></figure>
<table><tr><th>N</th><th>k_after</th><th>note</th></tr>
<tr><td>1e1000</td><td>inf</td><td>info</td></tr><tr><td>5</td><td>nan</td><td>-</td></tr>
<tr><td>7</td><td>None</td><td>-Infinity</td></tr></table>
<table class="autosummary longtable table"><tr><td>f</td><td>None means float64.</td></tr></table>
</article></body></html>
"""

CHAPTER_GOOD = """<!DOCTYPE html><html><body><article class="bd-article">
<figure id="fig-one"><img src="c.png"><figcaption><p><span class="caption-number">Fig. 1 </span>
Paper figure 9.</p></figcaption></figure>
<table><tr><th>N</th><th>k_after</th></tr><tr><td>10^1000</td><td>≈ 4.8045 × 10^501</td></tr>
<tr><td>infinite</td><td>information</td></tr></table>
</article></body></html>
"""


def _page(tmp_path, name, html):
    page = tmp_path / name
    page.parent.mkdir(parents=True, exist_ok=True)
    page.write_text(html)
    for img in ("a.png", "b.png", "c.png"):
        (page.parent / img).write_bytes(PNG)
    return page


def _static(tmp_path, name, html):
    page = _page(tmp_path, name, html)
    return check_book.check_page(page, tmp_path, CHROMIUM, {})[0]


@needs_chromium
def test_chapter_figures_need_a_numbered_caption_and_appear_once(tmp_path):
    problems = "\n".join(_static(tmp_path, "chapter.html", CHAPTER_BAD))
    assert "image 'a.png' is not in a numbered figure" in problems
    assert "figure 'fig-unnumbered' has no numbered caption" in problems
    assert "the image 'c.png' is shown twice on the page" in problems
    assert "fig-ok" not in problems
    assert _static(tmp_path, "good.html", CHAPTER_GOOD) == []


@needs_chromium
def test_placeholders_in_a_table_fail_but_words_and_autosummary_do_not(tmp_path):
    problems = _static(tmp_path, "chapter.html", CHAPTER_BAD)
    shown = sorted(p.split("table cell shows ")[1].split(":")[0] for p in problems
                   if "table cell shows" in p)
    assert shown == ["'-Infinity'", "'None'", "'inf'", "'nan'"]


@needs_chromium
def test_reference_pages_need_no_numbered_figures(tmp_path):
    html = CHAPTER_BAD.replace("<table", "<div").replace("</table>", "</div>")
    problems = "\n".join(_static(tmp_path, "api/json.html", html))
    assert "numbered" not in problems and "not in a numbered figure" not in problems


def _api_html(ids, links=()):
    body = "".join(f'<dt id="{i}">{i}</dt>' for i in ids)
    body += "".join(f'<a href="symhx.html#{target}">x</a>' for target in links)
    return f'<!DOCTYPE html><html><body><article class="bd-article">{body}</article></body></html>'


def test_an_api_page_that_misses_a_public_name_fails():
    import json

    names = list(json.__all__)
    scan = check_book.scan_html(_api_html([f"json.{n}" for n in names if n != "loads"]))
    (msg,) = check_book.api_page_problems("api/json.html", scan)
    assert msg == "api/json.html: the API page of json misses the public name(s) loads"
    complete = check_book.scan_html(_api_html([f"json.{n}" for n in names]))
    assert check_book.api_page_problems("api/json.html", complete) == []
    # a name documented on the page of the top-level package counts when it is linked
    linked = check_book.scan_html(_api_html([f"json.{n}" for n in names if n != "loads"],
                                            links=["json.loads"]))
    assert check_book.api_page_problems("api/json.html", linked) == []
    assert check_book.api_page_problems("chapter.html", scan) == []


def test_the_book_api_pages_are_current():
    """The committed pages list exactly the public names (scripts/make_api_pages.py)."""
    spec = importlib.util.spec_from_file_location(
        "make_api_pages_under_test", SCRIPT.parent / "make_api_pages.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.main(["--check"]) == 0


LAYOUT_BAD = """<!DOCTYPE html><html><head><style>
body { margin: 0 } article { width: 600px; margin-left: 50px }
pre { overflow: hidden; white-space: pre } .scroll { overflow-x: auto }
.wrap { white-space: pre-wrap }
</style></head><body><article class="bd-article">
<figure id="fig-wide"><img src="wide.png" style="max-width: 100%"></figure>
<figure id="fig-fits"><img src="narrow.png"></figure>
<pre id="clipped">{line} # cut off here</pre>
<div class="scroll"><pre id="scrolls">{line} # scrolls</pre></div>
<pre class="wrap">{line} # wraps</pre>
</article></body></html>
""".replace("{line}", "assert mpmath.almosteq(cp.p, mpmath.mpf(P_C_101), "
            "rel_eps=mpmath.mpf(10) ** -48)")


def _png(width, height):
    import struct
    import zlib

    raw = b"".join(b"\x00" + b"\xff\xff\xff" * width for _ in range(height))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2,
                                                              0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


@needs_driver
def test_layout_catches_a_shrunk_figure_and_a_clipped_code_block(tmp_path):
    (tmp_path / "wide.png").write_bytes(_png(1000, 40))    # shown at 520 px (figure margins)
    (tmp_path / "narrow.png").write_bytes(_png(560, 40))   # shown at its natural width
    page = tmp_path / "layout.html"
    page.write_text(LAYOUT_BAD)
    driver = check_book.make_driver(CHROMIUM, CHROMEDRIVER)
    try:
        problems = "\n".join(check_book.layout_problems(driver, page, tmp_path))
    finally:
        driver.quit()
    assert "figure shrunk to 0.52 of its natural width (1000 px" in problems  # 520 px box
    assert "narrow.png" not in problems
    # only the block that neither wraps nor scrolls (the other two have the same line)
    assert problems.count("code block clipped without a scroll bar") == 1
