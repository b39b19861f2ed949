#!/bin/sh
# Renders a small comparison report, opens it in headless Chromium, fails on any console
# message (errors, uncaught exceptions, files that do not load), and saves a screenshot.
# Skips (exit 0, saying so) where Chromium is not installed.
#
#   tests/report/check_report.sh [OUT_DIR]     (default: /tmp/lightlab-report-check)
set -eu

browser=""
for b in chromium chromium-browser google-chrome; do
    if command -v "$b" >/dev/null 2>&1; then browser="$b"; break; fi
done
if [ -z "$browser" ]; then
    echo "SKIP: no Chromium found (apt-get install chromium); report not checked in a browser"
    exit 0
fi

out="${1:-/tmp/lightlab-report-check}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
(cd "$root" && cargo build --release --quiet)
lightlab="$target/release/lightlab"

rm -rf "$out"
mkdir -p "$out"
"$lightlab" compare builtin:assignment --strategies light,cosine,bsdf --spp 4 \
    --reference-spp 64 --width 96 -o "$out/compare" >/dev/null 2>&1
"$lightlab" converge builtin:assignment --strategies light,cosine --max-spp 8 --seeds 2 \
    --width 32 -o "$out/converge" >/dev/null 2>&1

check() {
    page="$1"; shot="$2"
    log="$shot.log"
    # --enable-logging=stderr prints every console message as INFO:CONSOLE.
    timeout 120 "$browser" --headless --no-sandbox --disable-gpu --enable-logging=stderr \
        --v=0 --window-size=1280,1400 --virtual-time-budget=3000 \
        --screenshot="$shot" "file://$page" >"$log" 2>&1 || true
    if grep -q "CONSOLE" "$log"; then
        echo "FAIL: console messages on $page:"
        grep "CONSOLE" "$log"
        exit 1
    fi
    if [ ! -s "$shot" ]; then
        echo "FAIL: no screenshot of $page (see $log)"
        exit 1
    fi
    echo "ok: $page loads without console messages; screenshot $shot"
}

check "$out/compare/index.html" "$out/compare.png"
check "$out/converge/index.html" "$out/converge.png"

# The check must be able to fail: a copy of the report with a missing image.
cp -r "$out/compare" "$out/broken"
rm "$out/broken/img/light.js" "$out/broken/img/inset1-light.png"
if (check "$out/broken/index.html" "$out/broken.png") >/dev/null 2>&1; then
    echo "FAIL: the check did not notice missing files in $out/broken"
    exit 1
fi
echo "ok: a report with missing files is caught"
