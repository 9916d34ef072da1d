#!/usr/bin/env bash
# Opens an HTML report in headless Chromium (Debian's chromium, installed by scripts/install-deps)
# and checks that it renders: the parsed DOM holds the expected plots and text, and a screenshot
# is written with content. Usage: render_report.sh REPORT.html MIN_SVG TEXT...
set -euo pipefail
report="$1"; min_svg="$2"; shift 2
browser="$(command -v chromium || command -v chromium-browser || true)"
if [[ -z "$browser" ]]; then
  echo "render_report: no chromium on PATH (scripts/install-deps installs Debian's chromium)" >&2
  exit 1
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
flags=(--headless --no-sandbox --disable-gpu --disable-dev-shm-usage --user-data-dir="$out/profile")
timeout 120 "$browser" "${flags[@]}" --dump-dom "file://$(realpath "$report")" >"$out/dom.html" 2>/dev/null
svgs="$(grep -o '<svg' "$out/dom.html" | wc -l)"
if (( svgs < min_svg )); then
  echo "render_report: $svgs <svg> elements in the rendered DOM, expected at least $min_svg" >&2
  exit 1
fi
for text in "$@"; do
  if ! grep -q -- "$text" "$out/dom.html"; then
    echo "render_report: '$text' not in the rendered page" >&2
    exit 1
  fi
done
timeout 120 "$browser" "${flags[@]}" --window-size=1000,2000 --screenshot="$out/page.png" \
  "file://$(realpath "$report")" >/dev/null 2>&1
size="$(stat -c %s "$out/page.png")"
if (( size < 20000 )); then
  echo "render_report: screenshot only $size bytes" >&2
  exit 1
fi
echo "render_report: $svgs plots, screenshot $size bytes"
