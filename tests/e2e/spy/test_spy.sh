#!/usr/bin/env bash
# GIVEN Xvfb and a gpilot process publishing HEALTH, WHEN ./deploy/spy starts, THEN it loads every gpilot
# type from our jar, its window appears, and a screenshot of the decoded HEALTH channel is saved. The bus is
# signed (a bus key, as ./deploy/run makes): lcm-spy decodes the messages in front of their signatures.
set -u
build="$1"; ntypes="$2"
root="$(cd "$(dirname "$0")/../../.." && pwd)"
out="$build/e2e/spy"; mkdir -p "$out"
for t in Xvfb xdotool import java; do
  command -v "$t" >/dev/null || { echo "SKIPPED: $t not installed (deploy/setup installs it)"; exit 77; }
done
# Xvfb picks a free display itself and writes its number once it accepts connections (-displayfd): a random
# display and a second's sleep lost the race under load (one of the two lcm-spy windows could not connect).
rm -f "$out/display.txt"
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$out/display.txt" >/dev/null 2>&1 & xvfb=$!
health=""; spy=""
cleanup() { kill $spy $health 2>/dev/null; kill $xvfb 2>/dev/null; wait 2>/dev/null; }
trap cleanup EXIT
for _ in $(seq 1 100); do [ -s "$out/display.txt" ] && break; sleep 0.1; done
n="$(head -1 "$out/display.txt" 2>/dev/null | tr -d '[:space:]')"
[ -n "$n" ] || { echo "FAIL: Xvfb gave no display within 10 s"; exit 1; }
export DISPLAY=":$n"
rm -f "$out/bus.key"; "$build/bin/gpilot-keygen" "$out/bus.key" >/dev/null || { echo "FAIL: gpilot-keygen"; exit 1; }
GPILOT_BUS_KEY="$out/bus.key" "$build/bin/gpilot-health" --duration 30 >/dev/null & health=$!
"$root/deploy/spy" >"$out/spy.log" 2>&1 & spy=$!
win=""
for _ in $(seq 1 40); do
  win=$(xdotool search --name 'LCM Spy' 2>/dev/null | head -1)
  [ -n "$win" ] && grep -q "Found .* LCM types" "$out/spy.log" && break
  sleep 0.5
done
[ -n "$win" ] || { echo "FAIL: no 'LCM Spy' window"; cat "$out/spy.log"; exit 1; }
grep -q "^Found $ntypes LCM types" "$out/spy.log" || { echo "FAIL: expected 'Found $ntypes LCM types'"; cat "$out/spy.log"; exit 1; }
sleep 3  # a few HEALTH messages arrive
xdotool mousemove --window "$win" 60 27 click --repeat 2 1
sleep 2
import -window root "$out/lcm-spy.png"
kill -0 $spy 2>/dev/null || { echo "FAIL: lcm-spy exited"; cat "$out/spy.log"; exit 1; }
# AND a second lcm-spy watches the frames' URL (CAMERA travels on port + 1: bus.frames_url)
grep -q "for the frames, on udpm://239.255.76.67:7668" "$out/spy.log" || { echo "FAIL: no lcm-spy on the frames' URL"; cat "$out/spy.log"; exit 1; }
[ "$(xdotool search --name 'LCM Spy' 2>/dev/null | wc -l)" -ge 2 ] || { echo "FAIL: one 'LCM Spy' window, not two"; exit 1; }
grep -qi "exception" "$out/spy.log" && { echo "FAIL: lcm-spy raised an exception"; cat "$out/spy.log"; exit 1; }
echo "lcm-spy found $ntypes types; screenshot: $out/lcm-spy.png"
