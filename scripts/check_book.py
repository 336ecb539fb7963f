#!/usr/bin/env python3
"""Check the built symhx book in a real browser (headless Chromium).

Usage::

    python scripts/check_book.py [HTML_DIR] [--chromium /usr/bin/chromium] [--jobs 2]

``HTML_DIR`` defaults to ``book/_build/html``. Every HTML page of the build (outside ``_static``,
``_sources``, ``_images``) is opened with ``chromium --headless --dump-dom`` after its scripts
have run (``--virtual-time-budget=10000``), with Chromium's network log switched on. The check
fails (exit status 1, one line per problem) unless, for every page:

* **math is typeset**: a page whose HTML holds math (elements of class ``math``) has at least as
  many ``<mjx-container>`` elements after MathJax ran, no MathJax error (``mjx-merror``), and no
  raw TeX left in the visible text (``$$``, ``\\(``, ``\\)``, ``\\[``, ``\\]``, ``\\begin{``,
  a TeX control word such as ``\\frac`` or ``\\tilde``, a ``$...$`` pair outside code, or
  pseudo-LaTeX typed as text: ``Phi_{N,p}``, ``k_- <= k_+``), nor a MyST role left as text
  (``{py:func}``, ``{ref}``: a doubled role renders the first one literally);
* **nothing is clipped** (measured in the laid-out page: headless Chromium driven by Selenium and
  Debian's ``chromedriver``, windows 1280 and 800 px wide): no display equation or table is
  wider than the article's column (``scrollWidth > clientWidth``, or sticking out of the column)
  unless it sits in a horizontal scroll container (``overflow-x: auto|scroll``), no display
  equation starts left of its box (a centred equation wider than its box loses its left side),
  and at the desktop width (1280 px) nothing needs horizontal scrolling at all (a reader does
  not see that the right end of an equation is hidden behind a scroll bar);
* **images load in the browser**: every ``<img>`` has a non-zero ``naturalWidth``, and no
  ``<figure>`` renders an image area less than 20 px high;
* **figures have images**: every ``<figure>`` of the built page holds an ``<img>`` or ``<svg>``
  (a figure cell whose plot was not captured leaves an empty figure with its caption);
* **images load**: every ``<img src>`` (after scripts ran) is a local file of the build, non-empty
  and a PNG, JPEG, GIF, WebP or SVG image (``data:`` URIs are accepted);
* **figures are numbered and shown once**: every image of a chapter (in the article, outside the
  reference pages ``api/``, ``genindex``, ``search``, ``py-modindex``) sits in a ``<figure>``
  whose caption carries a number (``span.caption-number``, "Fig. 7"), and no image appears twice
  on a page (the same ``src``: a figure displayed twice);
* **tables hold numbers, not placeholders**: no cell of a rendered table (autosummary tables of
  the API pages excepted) reads ``inf``, ``-inf``, ``nan``, ``NaN``, ``None`` or ``Infinity``;
* **API pages are complete**: the page ``api/<module>.html`` documents or links every name of
  ``<module>.__all__`` (an element whose ``id`` is ``<module>.<name>`` or ``symhx.<name>``, or a
  link to one);
* **figures are legible and code is readable** (layout pass): no image of the article is shown
  at less than 0.8 of its natural width, and no code block (``<pre>``) is wider than its box
  unless it wraps or scrolls (``overflow-x: auto|scroll``);
* **nothing comes from the internet**: no ``src``/``href``/``srcset``/``data``/``poster`` of a
  resource (script, stylesheet, image, font, frame, media; ``<a href>`` and navigational
  ``<link rel>`` are allowed) points to ``http(s)://`` or ``//``, neither in the built file nor in
  the DOM after scripts ran, no local stylesheet pulls ``url(http...)`` or ``@import`` from the
  internet, every local script and stylesheet a page loads exists, and Chromium's network log shows
  no http(s) request initiated by the page (requests Chromium makes for itself, with initiator
  ``"not an origin"``, are ignored).

Exit status 2 means the check could not run (no build directory, no Chromium, no chromedriver or
selenium for the layout pass; ``--no-layout`` skips that pass explicitly).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--virtual-time-budget=10000",
    "--dump-dom",
    "--disable-quic",
    "--no-first-run",
    "--disable-component-update",
    "--disable-sync",
]
SKIP_DIRS = {"_static", "_sources", "_images", "_sphinx_design_static", ".doctrees"}
REMOTE = re.compile(r"^\s*(https?:)?//", re.I)
# <link rel=...> values that only name another document (no resource is fetched)
NAV_RELS = {"index", "search", "next", "prev", "previous", "canonical", "alternate", "author",
            "license", "help", "first", "last", "up", "bookmark", "external", "nofollow",
            "noopener", "noreferrer", "top", "contents", "start", "copyright", "glossary"}
# attributes through which a tag loads a resource
RESOURCE_ATTRS = {
    "script": ("src",), "img": ("src", "srcset"), "source": ("src", "srcset"),
    "iframe": ("src",), "frame": ("src",), "embed": ("src",), "object": ("data",),
    "video": ("src", "poster"), "audio": ("src",), "track": ("src",), "input": ("src",),
    "image": ("href", "xlink:href"), "use": ("href", "xlink:href"),
}
HIDDEN_TEXT_TAGS = {"script", "style", "pre", "code", "textarea", "noscript", "template",
                    "mjx-container", "mjx-assistive-mml", "svg", "math"}
RAW_TEX = [
    (re.compile(r"\$\$"), "$$"),
    (re.compile(r"\\\("), r"\("),
    (re.compile(r"\\\)"), r"\)"),
    (re.compile(r"\\\["), r"\["),
    (re.compile(r"\\\]"), r"\]"),
    (re.compile(r"\\begin\{"), r"\begin{"),
    (re.compile(r"\\[a-zA-Z]{2,}(?![a-zA-Z])"), r"\command"),
    # pseudo-LaTeX typed as text instead of maths: Phi_{N,p}, k_- <= k_+
    (re.compile(r"[A-Za-z)]_\{"), "x_{...} (pseudo-LaTeX)"),
    # (the names of the sample spaces "excess<=m" are identifiers, not maths)
    (re.compile(r"[\w)+-](?<!excess)\s*(<=|>=)\s*[\w(+-]"), "<= or >= (pseudo-LaTeX)"),
    (re.compile(r"(?<![\w$])\$[^$\s][^$\n]{0,80}?(?<=\S)\$(?![\w$])"), "$...$"),
]
#: a MyST role left as text (a doubled ``{py:func}{py:func}`x``` renders the first one
#: literally before the link)
RAW_ROLE = re.compile(r"\{(?:py:[a-z]+|ref|doc|numref|eq|term|download|math|cite)\}")
#: pseudo-LaTeX patterns: checked in the chapters, not in the reference pages, where docstrings
#: and --help texts write maths in plain ASCII (``k <= N``) as they do in a terminal
PSEUDO_TEX = {"x_{...} (pseudo-LaTeX)", "<= or >= (pseudo-LaTeX)"}
#: placeholder values that must never appear in a rendered table cell
PLACEHOLDER = re.compile(r"(?<![\w.])(-?inf|-?Infinity|nan|NaN|None)(?![\w])")
#: pages that are not chapters (no numbered figures required)
NOT_CHAPTERS = re.compile(r"^(api/|genindex\.html$|search\.html$|py-modindex\.html$)")
CSS_URL = re.compile(r"""url\(\s*['"]?([^'")]+)['"]?\s*\)|@import\s+['"]([^'"]+)['"]""", re.I)
IMAGE_MAGIC = (b"\x89PNG\r\n\x1a\n", b"\xff\xd8\xff", b"GIF87a", b"GIF89a")


@dataclass
class PageScan:
    """What an HTML parse of one page found."""

    resources: list[tuple[str, str, str]] = field(default_factory=list)  # (tag, attr, url)
    local_assets: list[tuple[str, str]] = field(default_factory=list)    # (tag, url) script/css
    images: list[str] = field(default_factory=list)
    math_elements: int = 0
    mjx_containers: int = 0
    mjx_errors: int = 0
    figures: int = 0
    empty_figures: list[str] = field(default_factory=list)  # ids of <figure> without an image
    inline_css: list[str] = field(default_factory=list)
    text: list[str] = field(default_factory=list)
    # images of the <article> and the figure each sits in (None: not in a figure)
    article_images: list[tuple[str, str | None]] = field(default_factory=list)
    numbered_figures: set[str] = field(default_factory=set)  # ids with a caption number
    table_cells: list[str] = field(default_factory=list)  # <td>/<th> texts (not autosummary)
    ids: set[str] = field(default_factory=set)
    hrefs: list[str] = field(default_factory=list)


class _Scanner(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.scan = PageScan()
        self._hidden: list[str] = []
        self._figures: list[list] = []  # open <figure>s: [id, has_image]
        self._article = 0  # depth of open <article> elements
        self._tables: list[bool] = []  # open <table>s: checked (not an autosummary table)?
        self._cell: list[str] | None = None  # text of the open <td>/<th>
        self._fig_counter = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k.lower(): (v or "") for k, v in attrs}
        s = self.scan
        classes = a.get("class", "").split()
        if "math" in classes:
            s.math_elements += 1
        if tag == "mjx-container":
            s.mjx_containers += 1
        if tag == "mjx-merror" or "data-mjx-error" in a:
            s.mjx_errors += 1
        if "style" in a:
            s.inline_css.append(a["style"])
        for attr in RESOURCE_ATTRS.get(tag, ()):
            if a.get(attr):
                for url in _srcset_urls(a[attr]) if attr == "srcset" else [a[attr]]:
                    s.resources.append((tag, attr, url))
        if tag == "link" and a.get("href"):
            rels = set(a.get("rel", "").lower().split())
            if not rels or not rels <= NAV_RELS:
                s.resources.append((tag, "href", a["href"]))
                if rels & {"stylesheet", "preload", "modulepreload"}:
                    s.local_assets.append((tag, a["href"]))
        if tag == "script" and a.get("src"):
            s.local_assets.append((tag, a["src"]))
        if tag == "img" and a.get("src"):
            s.images.append(a["src"])
        if tag == "figure":
            self.scan.figures += 1
            self._fig_counter += 1
            self._figures.append([a.get("id") or f"<figure {self._fig_counter}>", False])
        if tag in ("img", "svg", "object", "embed") and self._figures:
            self._figures[-1][1] = True
        if tag == "article":
            self._article += 1
        if tag == "img" and self._article and a.get("src"):
            s.article_images.append((a["src"], self._figures[-1][0] if self._figures else None))
        if "caption-number" in classes and self._figures:
            s.numbered_figures.add(self._figures[-1][0])
        if tag == "table":
            self._tables.append("autosummary" not in classes)
        if tag in ("td", "th") and self._tables and self._tables[-1]:
            self._cell = []
        if a.get("id"):
            s.ids.add(a["id"])
        if tag == "a" and a.get("href"):
            s.hrefs.append(a["href"])
        if tag in HIDDEN_TEXT_TAGS:
            self._hidden.append(tag)

    def handle_endtag(self, tag: str) -> None:
        if tag == "article" and self._article:
            self._article -= 1
        if tag == "table" and self._tables:
            self._tables.pop()
        if tag in ("td", "th") and self._cell is not None:
            self.scan.table_cells.append(" ".join("".join(self._cell).split()))
            self._cell = None
        if tag == "figure" and self._figures:
            fig_id, has_image = self._figures.pop()
            if not has_image:
                self.scan.empty_figures.append(fig_id)
        if tag in HIDDEN_TEXT_TAGS and tag in self._hidden:
            while self._hidden and self._hidden.pop() != tag:
                pass

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)
        if self._hidden:
            if self._hidden[-1] == "style":
                self.scan.inline_css.append(data)
            return
        self.scan.text.append(data)


def _srcset_urls(value: str) -> list[str]:
    return [part.strip().split()[0] for part in value.split(",") if part.strip()]


def scan_html(html: str) -> PageScan:
    parser = _Scanner()
    parser.feed(html)
    parser.close()
    return parser.scan


def _local_target(page: Path, url: str, root: Path) -> Path | None:
    """File that a relative URL of ``page`` names, or None if it is not a plain local path."""
    parts = urlsplit(url)
    if parts.scheme and parts.scheme != "file":
        return None
    path = unquote(parts.path)
    if not path:
        return None
    if parts.scheme == "file":
        return Path(path)
    return (root / path.lstrip("/")) if path.startswith("/") else (page.parent / path)


def _is_image(path: Path) -> bool:
    head = path.read_bytes()[:512]
    if head.startswith(IMAGE_MAGIC) or (head[:4] == b"RIFF" and head[8:12] == b"WEBP"):
        return True
    return b"<svg" in head.lower() or (head.lstrip().startswith(b"<?xml") and path.suffix == ".svg")


def _css_remote_urls(css: str) -> list[str]:
    css = re.sub(r"/\*.*?\*/", "", css, flags=re.S)
    found = []
    for m in CSS_URL.finditer(css):
        url = m.group(1) or m.group(2)
        if url and REMOTE.match(url):
            found.append(url.strip())
    return found


def page_requests(netlog: Path) -> list[str]:
    """http(s) URLs requested by the page itself (not by Chromium's own services)."""
    try:
        text = netlog.read_text(errors="replace")
    except OSError:
        return []
    try:
        data = json.loads(text)
    except json.JSONDecodeError:  # log not closed properly: close the event list ourselves
        try:
            data = json.loads(text.rstrip().rstrip(",") + "]}")
        except json.JSONDecodeError:
            return [f"<unreadable network log {netlog}>"]
    types = {v: k for k, v in data.get("constants", {}).get("logEventTypes", {}).items()}
    urls = []
    for ev in data.get("events", []):
        params = ev.get("params") or {}
        url = params.get("url", "")
        if types.get(ev.get("type")) != "URL_REQUEST_START_JOB" or not REMOTE.match(url):
            continue
        if params.get("initiator") == "not an origin":
            continue  # Chromium's own background traffic (updates, time, accounts)
        urls.append(url)
    return sorted(set(urls))


def run_chromium(chromium: str, page: Path, workdir: Path) -> tuple[str, list[str], str]:
    """Open ``page``; return (DOM after scripts, page-initiated http(s) requests, stderr tail)."""
    netlog = workdir / "netlog.json"
    cmd = [chromium, *CHROMIUM_FLAGS, f"--user-data-dir={workdir / 'profile'}",
           f"--log-net-log={netlog}", "--net-log-capture-mode=Default", page.resolve().as_uri()]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)
    return proc.stdout, page_requests(netlog), proc.stderr[-2000:]


PLOT_CALL = re.compile(r"^(?!\s*(from|import)\b).*\bplot_\w+\(", re.M)
CODE_CELL = re.compile(r"```\{code-cell\}[^\n]*\n(.*?)```", re.S)


def expected_plot_cells(page: Path, root: Path) -> int:
    """Code cells of the page's MyST source that call a ``plot_*`` function (each must render
    an image; a backend switched to Agg would lose them silently)."""
    source = root.parent.parent / page.relative_to(root).with_suffix(".md")
    if not source.is_file():
        return 0
    cells = CODE_CELL.findall(source.read_text(encoding="utf-8", errors="replace"))
    return sum(1 for cell in cells if PLOT_CALL.search(cell))


def check_page(page: Path, root: Path, chromium: str, css_cache: dict[Path, list[str]]
               ) -> tuple[list[str], dict]:
    rel = page.relative_to(root).as_posix()
    problems: list[str] = []
    source = scan_html(page.read_text(encoding="utf-8", errors="replace"))
    with tempfile.TemporaryDirectory(prefix="check_book_") as tmp:
        dom_html, requests, stderr = run_chromium(chromium, page, Path(tmp))
    if not dom_html.strip():
        return [f"{rel}: Chromium returned no DOM; stderr:\n{stderr}"], {}
    dom = scan_html(dom_html)

    # -- nothing from the internet
    for where, scan in (("built HTML", source), ("DOM after scripts", dom)):
        for tag, attr, url in scan.resources:
            if REMOTE.match(url):
                problems.append(f"{rel}: remote resource in {where}: <{tag} {attr}={url!r}>")
        for css in scan.inline_css:
            for url in _css_remote_urls(css):
                problems.append(f"{rel}: remote url in inline CSS ({where}): {url}")
    for url in requests:
        problems.append(f"{rel}: the page requested {url} (Chromium network log)")
    for tag, url in source.local_assets:
        if REMOTE.match(url):
            continue  # already reported
        target = _local_target(page, url, root)
        if target is None:
            continue
        if not target.is_file():
            problems.append(f"{rel}: <{tag}> asset {url!r} does not exist in the build")
        elif target.suffix == ".css":
            if target not in css_cache:
                css_cache[target] = _css_remote_urls(target.read_text(errors="replace"))
            for remote in css_cache[target]:
                problems.append(f"{rel}: stylesheet {url} loads {remote}")

    # -- figures hold images, and images load from local files
    for fig_id in source.empty_figures:
        problems.append(f"{rel}: <figure id={fig_id!r}> has no image (plot not captured?)")
    for src in dom.images:
        if src.startswith("data:"):
            continue
        if REMOTE.match(src):
            continue  # reported above
        target = _local_target(page, src, root)
        if target is None or not target.is_file():
            problems.append(f"{rel}: <img src={src!r}> does not resolve to a file of the build")
        elif target.stat().st_size == 0 or not _is_image(target):
            problems.append(f"{rel}: <img src={src!r}> is empty or not an image")

    # -- chapter figures are numbered, and no image is shown twice on a page
    if not NOT_CHAPTERS.match(rel):
        for src, fig_id in source.article_images:
            if fig_id is None:
                problems.append(f"{rel}: image {src!r} is not in a numbered figure (give its "
                                "cell mystnb figure metadata with a caption)")
            elif fig_id not in source.numbered_figures:
                problems.append(f"{rel}: figure {fig_id!r} has no numbered caption")
    seen: set[str] = set()
    for src, _ in source.article_images:
        if src in seen:
            problems.append(f"{rel}: the image {src!r} is shown twice on the page")
        seen.add(src)

    # -- tables hold numbers, not placeholders
    for cell in source.table_cells:
        m = PLACEHOLDER.search(cell)
        if m:
            problems.append(f"{rel}: table cell shows {m.group(1)!r}: {cell[:60]!r}")

    # -- an API page documents (or links) every public name of its module
    problems += api_page_problems(rel, source)

    # -- every code cell that draws with symhx.plots produced at least one image
    expected = expected_plot_cells(page, root)
    real_images = [s for s in dom.images if not s.startswith("data:")]
    if len(real_images) < expected:
        problems.append(f"{rel}: {expected} code cells call a plot_* function but only "
                        f"{len(real_images)} images were rendered (figures lost?)")

    # -- math typeset
    if source.math_elements:
        if dom.mjx_containers == 0:
            problems.append(f"{rel}: {source.math_elements} math elements but no <mjx-container>"
                            " after loading: MathJax did not typeset")
        elif dom.mjx_containers < source.math_elements:
            problems.append(f"{rel}: only {dom.mjx_containers} <mjx-container> for "
                            f"{source.math_elements} math elements")
    if dom.mjx_errors:
        problems.append(f"{rel}: {dom.mjx_errors} MathJax errors (mjx-merror)")
    text = "".join(dom.text)
    reference_page = rel.startswith("api/") or rel == "cli.html"
    for pattern, name in RAW_TEX:
        if reference_page and name in PSEUDO_TEX:
            continue
        m = pattern.search(text)
        if m:
            context = text[max(0, m.start() - 40): m.end() + 40].replace("\n", " ")
            problems.append(f"{rel}: raw TeX {name!r} in the rendered text: ...{context}...")
    m = RAW_ROLE.search(text)
    if m:
        context = text[max(0, m.start() - 40): m.end() + 40].replace("\n", " ")
        problems.append(f"{rel}: unrendered MyST role {m.group(0)!r} in the rendered text: "
                        f"...{context}...")
    stats = {"page": rel, "math": source.math_elements, "mjx": dom.mjx_containers,
             "images": len(dom.images), "figures": source.figures}
    return problems, stats


def api_page_problems(rel: str, scan: PageScan) -> list[str]:
    """Public names of the module of an API page (``api/<module>.html``) that the page neither
    documents nor links."""
    m = re.fullmatch(r"api/([\w.]+)\.html", rel)
    if not m:
        return []
    module = m.group(1)
    try:
        import importlib

        names = list(importlib.import_module(module).__all__)
    except Exception as exc:
        return [f"{rel}: cannot read the public names of {module}: {type(exc).__name__}: {exc}"]
    linked = {h.rsplit("#", 1)[1] for h in scan.hrefs if "#" in h}
    top = module.split(".")[0]
    missing = [n for n in names
               if not ({f"{module}.{n}", f"{top}.{n}"} & (scan.ids | linked))]
    return [f"{rel}: the API page of {module} misses the public name(s) {', '.join(missing)}"
            ] if missing else []


# --------------------------------------------------------------------------- layout (Selenium)
#: (width, height, strict): at desktop width every equation and table must fit its column without
#: horizontal scrolling; on a narrow window a horizontal scroll container is acceptable
WINDOW_SIZES = ((1280, 900, True), (800, 900, False))
CHROMEDRIVER = os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver")

#: JavaScript run in the laid-out page (after MathJax and the images): a list of problems.
LAYOUT_JS = r"""
const strict = arguments[0];  // true: everything must fit without scrolling
const done = arguments[arguments.length - 1];
const ready = (window.MathJax && MathJax.startup && MathJax.startup.promise)
    ? MathJax.startup.promise : Promise.resolve();
const imgs = Array.from(document.images).map(img => img.complete ? Promise.resolve()
    : new Promise(r => { img.onload = img.onerror = r; setTimeout(r, 5000); }));
Promise.all([ready, ...imgs]).then(() => {
  const problems = [];
  // the article's column (the first selector that matches, in this order of preference)
  const column = ['article.bd-article', 'main article', 'article', '[role=main]', 'main', 'body']
      .map(sel => document.querySelector(sel)).find(el => el);
  if (!column) { done([]); return; }  // e.g. a redirect page that is being replaced
  const colRect = column.getBoundingClientRect();
  const describe = el => {
    const t = (el.innerText || el.textContent || '').replace(/\s+/g, ' ').trim();
    const sec = el.closest('section[id]');
    return (sec ? '#' + sec.id + ': ' : '') + JSON.stringify(t.slice(0, 60));
  };
  const scroller = (el) => {
    for (let a = el; a && a !== column; a = a.parentElement) {
      const ox = getComputedStyle(a).overflowX;
      if ((ox === 'auto' || ox === 'scroll') && a.clientWidth > 0) return a;
    }
    return null;
  };
  // A display equation or table is fine when its visible box (its horizontal scroll container,
  // else itself) lies inside the column, and its content fits that box (a scroll container may
  // be overflowed to the right, never to the left: that part cannot be scrolled to).
  const check = (el, inner, what) => {
    const sc = scroller(el);
    const box = (sc || el).getBoundingClientRect();
    const ir = inner.getBoundingClientRect();
    if (box.left < colRect.left - 1 || box.right > colRect.right + 1) {
      problems.push(what + ' wider than its column, not in a scroll container: ' + describe(el));
    } else if (ir.left < box.left - 1) {
      problems.push(what + ' loses its left side (content starts left of its box): '
                    + describe(el));
    } else if (!sc && (ir.right > box.right + 1 || el.scrollWidth > el.clientWidth + 1)) {
      problems.push(what + ' clipped on the right, not in a scroll container: ' + describe(el));
    } else if (strict && (ir.right > colRect.right + 1 || ir.width > box.width + 1)) {
      problems.push(what + ' needs horizontal scrolling on a ' + window.innerWidth
                    + ' px wide window (right end hidden): ' + describe(el));
    }
  };
  for (const el of document.querySelectorAll('mjx-container[display="true"]')) {
    if (el.offsetParent === null) continue;
    check(el, el.querySelector('mjx-math') || el, 'display equation');
  }
  for (const el of document.querySelectorAll('table')) {
    if (el.offsetParent === null) continue;
    check(el, el, 'table');
  }
  for (const img of document.images) {
    if (!img.naturalWidth) problems.push('image did not load: ' + img.getAttribute('src'));
    else if (column.contains(img) && img.offsetParent !== null) {
      const scale = img.getBoundingClientRect().width / img.naturalWidth;
      if (scale < 0.8) problems.push('figure shrunk to ' + scale.toFixed(2)
        + ' of its natural width (' + img.naturalWidth + ' px; labels get too small): '
        + img.getAttribute('src'));
    }
  }
  for (const pre of column.querySelectorAll('pre')) {
    if (pre.offsetParent === null || pre.scrollWidth <= pre.clientWidth + 1) continue;
    const ws = getComputedStyle(pre).whiteSpace;
    if (['pre-wrap', 'pre-line', 'normal', 'break-spaces'].includes(ws)) continue;
    let scrolls = false;
    for (let a = pre; a && a !== column.parentElement; a = a.parentElement) {
      const ox = getComputedStyle(a).overflowX;
      if (ox === 'auto' || ox === 'scroll') { scrolls = a.scrollWidth > a.clientWidth; break; }
    }
    if (!scrolls) problems.push('code block clipped without a scroll bar: ' + describe(pre));
  }
  for (const fig of document.querySelectorAll('figure')) {
    const media = fig.querySelector('img, svg, object, embed');
    if (!media || media.getBoundingClientRect().height < 20) {
      problems.push('empty figure (no visible image): ' + (fig.id || describe(fig)));
    }
  }
  done(problems);
}).catch(err => done(['layout check failed in the page: ' + err]));
"""


def make_driver(chromium: str, chromedriver: str) -> Any:
    """A headless Chromium driven by Selenium (Debian's ``chromedriver``)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--disable-background-networking", "--no-first-run", "--hide-scrollbars",
                 "--disable-component-update", "--disable-sync"):
        opts.add_argument(flag)
    driver = webdriver.Chrome(service=Service(chromedriver), options=opts)
    driver.set_script_timeout(60)
    driver.set_page_load_timeout(60)
    return driver


def layout_problems(driver: Any, page: Path, root: Path) -> list[str]:
    """Clipped maths and tables, images that did not load and empty figures, measured in the
    laid-out page at every size of :data:`WINDOW_SIZES` (each problem reported once)."""
    rel = page.relative_to(root).as_posix()
    found: dict[str, int] = {}
    for width, height, strict in WINDOW_SIZES:
        driver.set_window_size(width, height)
        driver.get(page.resolve().as_uri())
        for msg in driver.execute_async_script(LAYOUT_JS, strict):
            found.setdefault(f"{rel}: {msg}", width)
    return [f"{msg} [window {width}px wide]" for msg, width in found.items()]


def pages_of(root: Path) -> list[Path]:
    pages = []
    for path in sorted(root.rglob("*.html")):
        if SKIP_DIRS & set(path.relative_to(root).parts[:-1]):
            continue
        pages.append(path)
    return pages


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("html_dir", nargs="?", default="book/_build/html")
    ap.add_argument("--chromium", default=os.environ.get("CHROMIUM", "/usr/bin/chromium"))
    ap.add_argument("--jobs", type=int, default=2, help="pages checked in parallel")
    ap.add_argument("--chromedriver", default=CHROMEDRIVER,
                    help="chromedriver for the layout pass (Debian: apt-get install "
                    "chromium-driver)")
    ap.add_argument("--no-layout", action="store_true",
                    help="skip the Selenium layout pass (clipped maths/tables, images)")
    args = ap.parse_args(argv)

    root = Path(args.html_dir)
    if not (root / "index.html").is_file() and not any(root.glob("*.html")):
        print(f"check_book: no built book at {root} (run jupyter-book build book)",
              file=sys.stderr)
        return 2
    chromium = args.chromium if Path(args.chromium).is_file() else shutil.which(args.chromium)
    if not chromium:
        print(f"check_book: Chromium not found at {args.chromium} "
              "(apt-get install -y chromium)", file=sys.stderr)
        return 2

    driver = None
    if not args.no_layout:
        chromedriver = (args.chromedriver if Path(args.chromedriver).is_file()
                        else shutil.which(args.chromedriver))
        if not chromedriver:
            print(f"check_book: chromedriver not found at {args.chromedriver} "
                  "(apt-get install -y chromium-driver), or pass --no-layout", file=sys.stderr)
            return 2
        try:
            driver = make_driver(chromium, chromedriver)
        except Exception as exc:  # selenium missing or the driver does not start
            print(f"check_book: cannot start Selenium with {chromedriver}: "
                  f"{type(exc).__name__}: {exc}", file=sys.stderr)
            return 2

    pages = pages_of(root)
    css_cache: dict[Path, list[str]] = {}
    try:
        with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            results = list(pool.map(lambda p: check_page(p, root, chromium, css_cache), pages))
        layout = [layout_problems(driver, p, root) for p in pages] if driver else []
    finally:
        if driver is not None:
            driver.quit()

    problems = [msg for page_problems, _ in results for msg in page_problems]
    problems += [msg for page_problems in layout for msg in page_problems]
    for _, stats in results:
        if stats:
            print(f"  {stats['page']:<28} math elements {stats['math']:4d}   "
                  f"mjx-container {stats['mjx']:4d}   figures {stats['figures']:3d}   "
                  f"images {stats['images']:3d}")
    if problems:
        print(f"\ncheck_book: FAILED, {len(problems)} problem(s) in {len(pages)} pages:",
              file=sys.stderr)
        for msg in problems:
            print("  - " + msg, file=sys.stderr)
        return 1
    print(f"check_book: OK, {len(pages)} pages: math typeset, images local and loaded, "
          "nothing requested from the internet"
          + ("" if args.no_layout else ", no clipped maths or tables"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
