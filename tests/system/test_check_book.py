"""scripts/check_book.py: the browser check of the built book catches what it promises to catch."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check_book.py"
spec = importlib.util.spec_from_file_location("check_book", SCRIPT)
check_book = importlib.util.module_from_spec(spec)
sys.modules.setdefault("check_book", check_book)
spec.loader.exec_module(check_book)

CHROMIUM = "/usr/bin/chromium" if Path("/usr/bin/chromium").is_file() else shutil.which("chromium")

BAD_PAGE = """<!DOCTYPE html><html><head>
<link rel="stylesheet" href="https://fonts.googleapis.com/css?family=Roboto">
<link rel="next" href="https://example.org/next.html">
<script src="https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-chtml.js"></script>
<script src="_static/missing.js"></script>
<style>body { background: url(https://example.org/bg.png) }</style>
</head><body>
<p>Some math: <span class="math notranslate nohighlight">\\(x^2\\)</span> and $$y$$.</p>
<p><a href="https://example.org/">a plain hyperlink is fine</a></p>
<img src="missing.png"><img src="notanimage.png"><img src="https://example.org/remote.png">
<figure id="fig-empty"><figcaption>A plot that was not captured</figcaption></figure>
<figure id="fig-ok"><img src="notanimage.png"></figure>
<pre>code may contain $$ and \\( freely</pre>
</body></html>
"""


def test_scan_html_finds_resources_and_text():
    scan = check_book.scan_html(BAD_PAGE)
    remote = {url for _, _, url in scan.resources if check_book.REMOTE.match(url)}
    assert "https://fonts.googleapis.com/css?family=Roboto" in remote
    assert "https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-chtml.js" in remote
    assert "https://example.org/remote.png" in remote
    assert "https://example.org/next.html" not in remote      # navigational link, not a load
    assert "https://example.org/" not in remote                # <a href>
    assert scan.math_elements == 1
    assert scan.figures == 2 and scan.empty_figures == ["fig-empty"]
    text = "".join(scan.text)
    assert "$$y$$" in text and "code may contain" not in text  # <pre> is not checked text
    assert check_book._css_remote_urls("".join(scan.inline_css)) == ["https://example.org/bg.png"]


def test_css_comments_are_not_read_as_urls():
    css = "/* see https://example.org/x.png */ a { background: url('img/local.png') }"
    assert check_book._css_remote_urls(css) == []
    assert check_book._css_remote_urls("@import 'https://x.org/a.css';") == ["https://x.org/a.css"]


def test_raw_tex_patterns_flag_leftover_tex_only():
    def hits(text):
        return [name for pattern, name in check_book.RAW_TEX if pattern.search(text)]

    assert hits("typeset text only") == []
    assert hits("costs 5 dollars") == []
    assert "$$" in hits("oops $$x$$")
    assert "$...$" in hits("oops $N$ left")
    assert r"\(" in hits(r"oops \(x\)")


def test_a_myst_role_left_as_text_is_flagged():
    assert check_book.RAW_ROLE.search("see {py:func}symhx.phi() and {ref}here")
    assert not check_book.RAW_ROLE.search("sets {N} and {k: k <= N} and f{x}")


def test_missing_build_dir_is_a_setup_error(tmp_path):
    assert check_book.main([str(tmp_path / "nothing")]) == 2


@pytest.mark.skipif(CHROMIUM is None, reason="needs Chromium (apt-get install chromium)")
def test_browser_check_reports_every_problem(tmp_path, capsys):
    (tmp_path / "index.html").write_text(BAD_PAGE)
    (tmp_path / "notanimage.png").write_text("hello")
    assert check_book.main([str(tmp_path), "--chromium", CHROMIUM]) == 1
    err = capsys.readouterr().err
    assert "fonts.googleapis.com" in err
    assert "cdn.jsdelivr.net" in err
    assert "example.org/bg.png" in err
    assert "Chromium network log" in err          # the browser really tried to fetch
    assert "_static/missing.js" in err
    assert "missing.png" in err and "not an image" in err
    assert "no <mjx-container>" in err
    assert "raw TeX '$$'" in err
    assert "example.org/next.html" not in err
    assert "<figure id='fig-empty'> has no image" in err
    assert "<figure id='fig-ok'>" not in err  # it has an <img> in the HTML ...
    assert "empty figure (no visible image): fig-ok" in err  # ... which does not load
    assert "image did not load: missing.png" in err


@pytest.mark.skipif(CHROMIUM is None, reason="needs Chromium (apt-get install chromium)")
def test_browser_check_passes_a_clean_page(tmp_path, capsys):
    png = (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00"
           b"\x00\x1f\x15\xc4\x89\x00\x00\x00\rIDATx\x9cc\xf8\x0f\x00\x00\x01\x01\x00\x05\x18\xd8N"
           b"\x00\x00\x00\x00IEND\xaeB`\x82")
    (tmp_path / "dot.png").write_bytes(png)
    (tmp_path / "index.html").write_text(
        '<html><body><p>No math here.</p><img src="dot.png">'
        '<a href="https://example.org/">link</a></body></html>')
    assert check_book.main([str(tmp_path), "--chromium", CHROMIUM]) == 0
    assert "check_book: OK" in capsys.readouterr().out


# --------------------------------------------------------------------------- what a reader sees
CHROMEDRIVER = shutil.which("chromedriver") or (
    "/usr/bin/chromedriver" if Path("/usr/bin/chromedriver").is_file() else None)
needs_driver = pytest.mark.skipif(CHROMIUM is None or CHROMEDRIVER is None,
                                  reason="needs chromium and chromium-driver (apt-get)")

# A page laid out like the book's theme: a 600 px article column; an equation wider than it
# centred in a box that hides overflow (loses its left side), one in a scroll container that a
# desktop reader must scroll, a table sticking out, a broken image, an empty figure, raw TeX and
# pseudo-LaTeX left in the text.
LAYOUT_BAD = """<!DOCTYPE html><html><head><style>
body { margin: 0 } article { width: 600px; margin-left: 100px }
.math { overflow: hidden; text-align: center } .scroll { overflow-x: auto }
.wide { display: inline-block; width: 900px; flex-shrink: 0; background: #eee }
mjx-container[display="true"] { display: flex; justify-content: center }
</style></head><body><article class="bd-article">
<section id="eq-left"><div class="math"><mjx-container display="true">
  <mjx-math class="wide">LEFT-CUT</mjx-math></mjx-container></div></section>
<section id="eq-scroll"><div class="scroll"><mjx-container display="true" style="display:block">
  <mjx-math class="wide">SCROLLS</mjx-math></mjx-container></div></section>
<section id="tab"><table style="width: 900px"><tr><th>N</th><th>jump</th></tr></table></section>
<p>The correction is $\\tilde\\chi_u = \\tfrac{a}{b}$ and Phi_{N,p} with k_- <= k_+.</p>
<p>The space excess<=6 is a name, not maths.</p>
<img src="broken.png">
<figure id="fig-blank">
  <img src="data:image/gif;base64,R0lGODlhAQABAAAAACw=" style="height:0"></figure>
</article></body></html>
"""

LAYOUT_GOOD = """<!DOCTYPE html><html><head><style>
body { margin: 0 } article { width: 600px; margin-left: 100px }
.scroll { overflow-x: auto } .narrow { display: inline-block; width: 300px }
</style></head><body><article class="bd-article">
<div class="math"><mjx-container display="true" style="display:block; text-align:center">
  <mjx-math class="narrow">FITS</mjx-math></mjx-container></div>
<div class="scroll"><table style="width: 500px"><tr><th>N</th><th>jump</th></tr></table></div>
<p>Plain text with a price of 5 dollars, and the space excess<=6.</p>
</article></body></html>
"""


@needs_driver
def test_layout_pass_catches_what_a_reader_sees(tmp_path):
    page = tmp_path / "bad.html"
    page.write_text(LAYOUT_BAD)
    driver = check_book.make_driver(CHROMIUM, CHROMEDRIVER)
    try:
        problems = check_book.layout_problems(driver, page, tmp_path)
        (tmp_path / "good.html").write_text(LAYOUT_GOOD)
        clean = check_book.layout_problems(driver, tmp_path / "good.html", tmp_path)
    finally:
        driver.quit()
    text = "\n".join(problems)
    assert "display equation loses its left side (content starts left of its box): #eq-left" \
        in text
    assert "needs horizontal scrolling on a 1280 px" in text and "SCROLLS" in text
    assert "table wider than its column" in text
    assert "image did not load: broken.png" in text
    assert "empty figure (no visible image): fig-blank" in text
    assert clean == []


def test_raw_tex_patterns_flag_tex_commands_and_pseudo_latex():
    def hits(text):
        return [name for pattern, name in check_book.RAW_TEX if pattern.search(text)]

    assert r"\command" in hits(r"is $\tilde\chi_u = \tfrac{a}{b}")  # book/forcing.md defect
    assert "x_{...} (pseudo-LaTeX)" in hits("neighbouring Phi_{N,p}: positive")
    assert "<= or >= (pseudo-LaTeX)" in hits("check k_- <= k_+ here")
    assert hits("the space excess<=6 and a path C:/x") == []
