#!/usr/bin/env bash
# Build the symhx book strictly and check it in headless Chromium.
#
# Assumes the book extra is installed (pip install ".[book]"). Run from anywhere:
#     bash scripts/ci_book.sh
# Installs Debian's chromium and chromium-driver with apt-get when missing (needs root).
set -euo pipefail
cd "$(dirname "$0")/.."

# the browser check needs Chromium and its WebDriver (Debian's packages)
if [ ! -x /usr/bin/chromium ] || [ ! -x /usr/bin/chromedriver ]; then
    echo "ci_book: installing chromium and chromium-driver (apt-get)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends chromium chromium-driver >/dev/null
fi

# Notebooks draw their figures with matplotlib's inline backend, which ipykernel selects only if
# MPLBACKEND is unset: an MPLBACKEND=Agg exported for the test suite would make every figure
# vanish from the book (check_book.py would then fail on the empty <figure> elements).
unset MPLBACKEND

start=$(date +%s)
# -W: warnings (including a failing cell) are errors; -n: nitpicky cross-references;
# --keep-going: report every problem, not just the first. A fresh build every time.
rm -rf book/_build
jupyter-book build book -W -n --keep-going
echo "ci_book: book built in $(( $(date +%s) - start )) s"

python scripts/check_book.py book/_build/html
