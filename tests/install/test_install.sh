#!/usr/bin/env bash
# `cmake --install` gives a tree that works without the checkout (issue 15, "A package a drone can install").
# Usage: test_install.sh SOURCE_DIR BUILD_DIR   (ctest: install_tree; the binaries must be built)
#   1. installs BUILD_DIR into a temporary prefix and moves the tree elsewhere (no path is compiled in);
#   2. in a private mount and network namespace in which SOURCE_DIR and BUILD_DIR are empty folders, from an
#      empty working directory (the build tree hidden first: it may be inside the checkout): gpilot-config
#      --defaults and gpilot-eval-hands --scenario tour give the build tree's answers; the installed
#      default.yaml is accepted; every installed scenario loads; a binary whose share/ is missing fails (so the checkout really is out of
#      reach); a CMake project finds gesture_pilot and builds against its types; a short
#      pipeline (gpilot-launch, scenario tour, simulator) writes a log that the installed Python types read.
#   The installed systemd units pass systemd-analyze verify (where it exists).
# Exits 77 (ctest: skipped) where no namespace can be made.
set -euo pipefail
src="$(realpath "$1")"; build="$(realpath "$2")"
fail() { echo "test_install: FAIL: $*" >&2; exit 1; }

if [ "${GPILOT_INSTALL_TEST_INNER:-}" != 1 ]; then
  tmp="$(mktemp -d /tmp/gpilot-install-test.XXXXXX)"
  trap 'rm -rf "$tmp"' EXIT
  cmake --install "$build" --prefix "$tmp/first" > "$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install"; }
  if command -v systemd-analyze > /dev/null; then  # before the move: the units name the install prefix
    systemd-analyze verify "$tmp"/first/lib/systemd/system/gpilot-*.service || fail "systemd-analyze verify of the units"
  fi
  mv "$tmp/first" "$tmp/prefix"
  p="$tmp/prefix"
  # What the tree holds: every gpilot-* binary of the build, the data, the units, the types.
  for exe in "$build"/bin/gpilot-*; do
    [ -x "$p/bin/$(basename "$exe")" ] || fail "bin/$(basename "$exe") not installed"
  done
  for f in share/gesture-pilot/data/skin/skin_model.yaml share/gesture-pilot/data/skin/synthetic_skin_tones.csv \
           share/gesture-pilot/data/people/astronaut.png share/gesture-pilot/data/backgrounds/building.jpg \
           share/gesture-pilot/data/README.md share/gesture-pilot/deploy/config/default.yaml \
           share/gesture-pilot/deploy/config/synthetic.yaml share/gesture-pilot/deploy/scenarios/tour.yaml \
           share/gesture-pilot/deploy/services.yaml lib/cmake/gesture_pilot/gesture_pilotConfig.cmake \
           lib/python3/dist-packages/gpilot/__init__.py lib/python3/dist-packages/gpilot_lcmlog.py \
           share/gesture-pilot/models/pose/pose_landmark_lite.onnx share/gesture-pilot/models/pose/pose_landmark_full.onnx \
           share/gesture-pilot/models/pose/pose_detection.onnx share/gesture-pilot/models/pose/LICENSE \
           share/gesture-pilot/models/pose/NOTICE; do
    [ -f "$p/$f" ] || fail "$f not installed"
  done
  ntypes=$(ls "$src"/lcmtypes/*.lcm | wc -l)
  [ "$(ls "$p"/include/gpilot/*.hpp | wc -l)" = "$ntypes" ] || fail "include/gpilot: not the $ntypes types"
  [ "$(ls "$p"/lib/python3/dist-packages/gpilot/*_t.py | wc -l)" = "$ntypes" ] || fail "python gpilot: not the $ntypes types"
  [ "$(ls "$p"/lib/systemd/system/gpilot-*.service | wc -l)" = 5 ] || fail "not the 5 units"
  # The units name the prefix they were installed into (the one place a path is written at install time).
  grep -q "^ExecStart=$tmp/first/bin/gpilot-flight " "$p/lib/systemd/system/gpilot-flight.service" \
    || fail "the units do not run the installed binaries"
  # The answers the installed binaries must give: the build tree's (timings aside).
  (cd "$tmp" && "$build/bin/gpilot-eval-hands" --scenario tour --stride 50 --png-dir '' --json 2>/dev/null) \
    > "$tmp/eval-build.json" || fail "gpilot-eval-hands from the build tree"
  "$build/bin/gpilot-config" --defaults > "$tmp/defaults-build.yaml" || fail "gpilot-config from the build tree"
  inner="mount -t tmpfs none \"\$2\" && mount -t tmpfs none \"\$1\" && ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec \"\$0\" \"\$@\""
  cp "$0" "$tmp/test_install.sh"  # this script is in the checkout, which is about to disappear
  export GPILOT_INSTALL_TEST_INNER=1 GPILOT_INSTALL_TEST_TMP="$tmp"
  unset GPILOT_ROOT GPILOT_BUS_KEY
  if [ "$(id -u)" = 0 ]; then
    unshare -m -n bash -c "$inner" "$tmp/test_install.sh" "$src" "$build" && exit 0 || exit $?
  elif unshare -rmn true 2>/dev/null; then
    unshare -rmn bash -c "$inner" "$tmp/test_install.sh" "$src" "$build" && exit 0 || exit $?
  fi
  echo "test_install: SKIPPED: cannot make a mount and network namespace to hide the checkout" >&2
  exit 77
fi

# Inside: the checkout and the build tree are empty folders now (the outer instance removes $tmp).
tmp="$GPILOT_INSTALL_TEST_TMP"; p="$tmp/prefix"; s="$p/share/gesture-pilot"
for d in "$src" "$build"; do
  [ ! -e "$d" ] || [ -z "$(ls -A "$d")" ] || fail "$d is still visible"
done
mkdir "$tmp/work" && cd "$tmp/work"

"$p/bin/gpilot-config" --defaults > defaults.yaml || fail "gpilot-config --defaults"
cmp -s defaults.yaml "$tmp/defaults-build.yaml" || fail "installed gpilot-config --defaults differs from the build tree's"
"$p/bin/gpilot-config" --config "$s/deploy/config/default.yaml" > /dev/null 2>&1 \
  || fail "installed gpilot-config does not accept the installed default.yaml"

"$p/bin/gpilot-eval-hands" --scenario tour --stride 50 --png-dir '' --json 2> eval.err > eval.json \
  || { cat eval.err >&2; fail "installed gpilot-eval-hands --scenario tour"; }
python3 - "$tmp/eval-build.json" eval.json <<'PY' || fail "installed gpilot-eval-hands differs from the build tree's"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
for d in (a, b):
    for k in [k for k in d if k.startswith("ms_per_frame")]: del d[k]
assert a == b and a["frames"] > 0, (a, b)
PY
# Every installed scenario loads (its backdrop, face and skin tones are installed too).
for f in "$s"/deploy/scenarios/*.yaml; do
  n="$(basename "$f" .yaml)"
  "$p/bin/gpilot-eval-hands" --scenario "$n" --stride 500 --png-dir '' --json 2> /dev/null > scenario.json \
    && python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["frames"] > 0' scenario.json \
    || fail "installed gpilot-eval-hands --scenario $n"
done
# Negative control: the same binary without its share/ has no data to fall back on.
mkdir -p bare/bin && cp "$p/bin/gpilot-eval-hands" bare/bin/
if bare/bin/gpilot-eval-hands --scenario tour --stride 50 --png-dir '' > /dev/null 2>&1; then
  fail "a binary without share/gesture-pilot still found its data (the checkout is not out of reach)"
fi

# Another project builds against the installed message types.
mkdir consumer && cat > consumer/CMakeLists.txt <<'CM'
cmake_minimum_required(VERSION 3.25)
project(consumer CXX)
find_package(gesture_pilot REQUIRED)
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE gesture_pilot::lcmtypes)
CM
cat > consumer/main.cpp <<'CPP'
#include <gpilot/gesture_cmd_t.hpp>
#include <vector>
int main() {
  gpilot::gesture_cmd_t in{}, out{};
  in.mode = gpilot::gesture_cmd_t::MODE_UP;
  std::vector<unsigned char> buf(in.getEncodedSize());
  in.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return out.decode(buf.data(), 0, static_cast<int>(buf.size())) == static_cast<int>(buf.size()) && out.mode == 2 ? 0 : 1;
}
CPP
cmake -S consumer -B consumer/build -DCMAKE_PREFIX_PATH="$p" > consumer.log 2>&1 \
  && cmake --build consumer/build >> consumer.log 2>&1 && consumer/build/consumer \
  || { cat consumer.log >&2; fail "a project using find_package(gesture_pilot)"; }

# A short pipeline from the installed tree (loopback only), its log read with the installed Python types.
"$p/bin/gpilot-keygen" bus.key > /dev/null && export GPILOT_BUS_KEY="$PWD/bus.key"
"$p/bin/gpilot-launch" --duration 6 --engage --var config="$s/deploy/config/synthetic.yaml" \
  --var source_flag=--synthetic --var source=deploy/scenarios/tour.yaml --var capture_extra= --var backend=sim \
  --var mavlink=udp:127.0.0.1:14580 --var log="$PWD/log.lcmlog" --var video_out= > launch.log 2>&1 \
  || { tail -20 launch.log >&2; fail "gpilot-launch from the installed tree"; }
PYTHONPATH="$p/lib/python3/dist-packages" python3 - log.lcmlog <<'PY' || { tail -20 launch.log >&2; fail "the pipeline's log"; }
import sys
from collections import Counter
from gpilot_lcmlog import EventLog
from gpilot import hand_obs_t, gesture_cmd_t, flight_setpoint_t
n = Counter()
for e in EventLog(sys.argv[1]):
    t = {"HAND_OBS": hand_obs_t, "GESTURE_CMD": gesture_cmd_t, "FLIGHT_SETPOINT": flight_setpoint_t}.get(e.channel)
    if t:
        t.decode(e.data)
        n[e.channel] += 1
print("test_install: pipeline log:", dict(n))
assert n["HAND_OBS"] >= 25 and n["GESTURE_CMD"] >= 25 and n["FLIGHT_SETPOINT"] >= 25, n
PY
rm -f log.lcmlog

echo "test_install: OK" >&2
