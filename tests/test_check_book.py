"""scripts/check_book.py: the browser check of the built book catches what it promises to catch."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "check_book.py"
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


def test_css_comments_are_ignored():
    css = "/* see https://example.org/x.png */ a { background: url('img/local.png') }"
    assert check_book._css_remote_urls(css) == []
    assert check_book._css_remote_urls("@import 'https://x.org/a.css';") == ["https://x.org/a.css"]


def test_raw_tex_patterns():
    def hits(text):
        return [name for pattern, name in check_book.RAW_TEX if pattern.search(text)]

    assert hits("typeset text only") == []
    assert hits("costs 5 dollars") == []
    assert "$$" in hits("oops $$x$$")
    assert "$...$" in hits("oops $N$ left")
    assert r"\(" in hits(r"oops \(x\)")


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
    assert "fig-empty" in err and "fig-ok" not in err


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
