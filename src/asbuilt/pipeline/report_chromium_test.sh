#!/usr/bin/env bash
# report.html in a real browser: surveys a Blender room (exact labels, fast),
# opens the report in headless Chromium, checks that no console error was
# logged, that the page holds the plan and the tables, and that a screenshot
# is written. Usage: report_chromium_test.sh ASBUILT SHARED_DATA_DIR
set -euo pipefail
asbuilt=$1
room=$2/blender-rooms-public/p01_rect_1door_2win
browser=$(command -v chromium || command -v chromium-browser || true)
if [[ -z $browser ]]; then echo "chromium not installed"; exit 77; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$asbuilt" survey "$room/capture.json" -o "$work/out" --capture-labels --report-frames 2 -q
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
       --disable-component-update --disable-sync --user-data-dir="$work/profile" --enable-logging=stderr --v=0)
timeout 120 "$browser" "${flags[@]}" --window-size=1300,1800 --screenshot="$work/shot.png" \
  "file://$work/out/report.html" > "$work/browser.log" 2>&1 || true
timeout 120 "$browser" "${flags[@]}" --dump-dom "file://$work/out/report.html" > "$work/dom.html" 2>> "$work/browser.log" || true
if grep -E 'CONSOLE\(|Uncaught|Failed to load resource' "$work/browser.log"; then
  echo "FAIL: the report logged console errors"; exit 1
fi
[[ -s $work/shot.png && $(stat -c %s "$work/shot.png") -gt 20000 ]] || { echo "FAIL: no screenshot"; cat "$work/browser.log"; exit 1; }
for needle in 'Floor plan' 'image/svg+xml;base64' 'Accuracy against the truth plan' 'Stage timings' 'door 0'; do
  grep -q "$needle" "$work/dom.html" || { echo "FAIL: the rendered page lacks '$needle'"; exit 1; }
done
echo "report.html loads in Chromium with no console errors; screenshot $(stat -c %s "$work/shot.png") bytes"
