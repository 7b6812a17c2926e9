#!/usr/bin/env bash
# report.html renders in a real browser: a small run (scenarios/small.yaml, partial maps, one
# playback run: a few seconds) writes its results folder and report.html; headless Chromium
# then loads file://.../report.html and
#   (a) takes a 1280 x 2000 screenshot: the PNG exists with exactly that size (read from its IHDR);
#   (b) dumps the DOM after the load event: the body's data-images attribute, set by the page's
#       script, says every image decoded ("N/N", N = the number of PNGs under the folder, > 0);
#   (c) logs the page's console (--enable-logging=stderr): the page logs nothing, so any console
#       line (an error, an uncaught exception, a refused external load) fails the test. A page
#       that does log an error is loaded first, to prove that such lines are seen at all.
# The page must also be self-contained: no http(s) or file: references in it.
# Chromium missing is a failure, not a skip: CI installs it (scripts/install_deps.sh --test).
# Usage: report_browser_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

browser=$(command -v chromium || command -v chromium-browser || true)
[ -n "$browser" ] || die "chromium is not installed: apt-get install chromium (scripts/install_deps.sh --test installs it)"

# Headless Chromium, in a profile of its own, with the page's console on stderr.
chrome() {  # chrome <stderr file> <args...>
  local log="$1"
  shift
  timeout 120 "$browser" --headless --no-sandbox --disable-gpu --no-first-run \
    --disable-extensions --user-data-dir="$tmp/profile" --enable-logging=stderr --v=0 "$@" \
    2>"$log"
}
console_lines() { grep -E ':CONSOLE(\(|:|\])' "$1" || true; }

# The console check sees a console error and an uncaught exception.
cat >"$tmp/bad.html" <<'EOF'
<!DOCTYPE html><html><body><script>console.error("report test probe"); no_such_function();</script></body></html>
EOF
chrome "$tmp/bad.err" --dump-dom "file://$tmp/bad.html" >/dev/null
console_lines "$tmp/bad.err" | grep -q 'report test probe' ||
  die "the console check does not see console.error (Chromium's log format changed?): $(tail -5 "$tmp/bad.err")"
console_lines "$tmp/bad.err" | grep -q 'Uncaught' ||
  die "the console check does not see uncaught exceptions: $(tail -5 "$tmp/bad.err")"

cd "$src" || exit 1
out="$tmp/run"
run small run scenarios/small.yaml --mode partial --repeats 1 --jobs 2 --out "$out"
page="$out/report.html"
[ -s "$page" ] || die "no $page"
grep -qF "report: $page" "$tmp/small.out" || die "retrace run does not say where the report is"

pngs=$(find "$out" -name '*.png' | wc -l)
embedded=$(grep -o 'src="data:image/png;base64,' "$page" | wc -l)
[ "$pngs" -gt 0 ] || die "the run wrote no figures"
[ "$embedded" -eq "$pngs" ] || die "$embedded images embedded, $pngs PNGs in the folder"
if grep -qiE '(src|href)="(https?:|file:|//)' "$page"; then
  die "the page refers to something outside itself: $(grep -oiE '(src|href)="(https?:|file:|//)[^"]{0,60}' "$page" | head -3)"
fi

# (a) The screenshot, exactly the window's size.
chrome "$tmp/shot.err" --window-size=1280,2000 --screenshot="$tmp/shot.png" "file://$page" \
  >/dev/null
[ -s "$tmp/shot.png" ] || die "no screenshot: $(tail -5 "$tmp/shot.err")"
read -r w3 w2 w1 w0 h3 h2 h1 h0 < <(od -An -tu1 -j16 -N8 "$tmp/shot.png")
width=$(((w3 << 24) | (w2 << 16) | (w1 << 8) | w0))
height=$(((h3 << 24) | (h2 << 16) | (h1 << 8) | h0))
[ "$width" -eq 1280 ] && [ "$height" -eq 2000 ] || die "screenshot is ${width}x${height}, not 1280x2000"

# (b) Every image decoded.
chrome "$tmp/dom.err" --virtual-time-budget=10000 --dump-dom "file://$page" >"$tmp/dom.html"
decoded=$(grep -oE '<body[^>]* data-images="[0-9]+/[0-9]+"' "$tmp/dom.html" | grep -oE '[0-9]+/[0-9]+')
[ -n "$decoded" ] || die "the body has no data-images attribute (the page's script did not run): $(head -c 300 "$tmp/dom.html")"
[ "$decoded" = "$pngs/$pngs" ] || die "images decoded: $decoded, expected $pngs/$pngs"

# (c) Nothing on the console in either load.
errors=$(console_lines "$tmp/shot.err"; console_lines "$tmp/dom.err")
[ -z "$errors" ] || die "console output: $errors"

echo "report.html: $embedded images embedded, $decoded decoded, screenshot ${width}x${height}," \
  "no console output ($(wc -c <"$page") bytes)"
