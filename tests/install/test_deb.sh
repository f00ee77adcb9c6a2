#!/usr/bin/env bash
# `cpack -G DEB` makes gesture-pilot_<version>_<arch>.deb that installs under /usr: every gpilot-* binary of the
# build, the data, the units (the committed deploy/systemd/*.service: they are written for /usr), the types,
# maintainer scripts that parse, Depends with the runtime libraries and deploy/runtime-packages; the binaries
# unpacked from it (stripped) run and find their data beside them; as root, the maintainer scripts are run
# against a private copy of /etc (the user, config, key; a stage started as the user with them; purge).
# Usage: test_deb.sh SOURCE_DIR BUILD_DIR   (ctest: install_deb; the binaries must be built)
set -euo pipefail
src="$(realpath "$1")"; build="$(realpath "$2")"
tmp="$(mktemp -d /tmp/gpilot-deb-test.XXXXXX)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "test_deb: FAIL: $*" >&2; exit 1; }
command -v dpkg-deb > /dev/null || { echo "test_deb: SKIPPED: no dpkg-deb" >&2; exit 77; }

(cd "$build" && cpack -G DEB -B "$tmp/out" > "$tmp/cpack.log" 2>&1) || { cat "$tmp/cpack.log" >&2; fail "cpack -G DEB"; }
debs=("$tmp"/out/gesture-pilot_*.deb)
[ "${#debs[@]}" = 1 ] && [ -f "${debs[0]}" ] || fail "no single gesture-pilot_*.deb in $(ls "$tmp/out")"
deb="${debs[0]}"
dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./||' > "$tmp/contents"

for exe in "$build"/bin/gpilot-*; do
  grep -qx "usr/bin/$(basename "$exe")" "$tmp/contents" || fail "usr/bin/$(basename "$exe") not in the package"
done
for f in usr/share/gesture-pilot/data/skin/skin_model.yaml usr/share/gesture-pilot/deploy/config/default.yaml \
         usr/share/gesture-pilot/deploy/scenarios/tour.yaml usr/share/gesture-pilot/deploy/services.yaml \
         usr/share/gesture-pilot/data/people/astronaut.png usr/include/gpilot/gesture_cmd_t.hpp \
         usr/lib/cmake/gesture_pilot/gesture_pilotConfig.cmake usr/lib/python3/dist-packages/gpilot/hand_obs_t.py \
         usr/lib/python3/dist-packages/gpilot_lcmlog.py usr/share/gesture-pilot/models/pose/pose_landmark_lite.onnx \
         usr/share/gesture-pilot/models/pose/pose_detection.onnx usr/share/gesture-pilot/models/pose/NOTICE \
         usr/share/gesture-pilot/models/pose/LICENSE; do
  grep -qx "$f" "$tmp/contents" || fail "$f not in the package"
done
[ -f "$build/gpilot_lcmtypes.jar" ] && { grep -qx usr/share/java/gpilot_lcmtypes.jar "$tmp/contents" || fail "the jar is not in the package"; }

mkdir "$tmp/root" && dpkg-deb -x "$deb" "$tmp/root"
units=0
for u in "$src"/deploy/systemd/*.service; do
  units=$((units + 1))
  cmp -s "$u" "$tmp/root/usr/lib/systemd/system/$(basename "$u")" || fail "packaged $(basename "$u") is not deploy/systemd's"
done
[ "$units" = 5 ] && [ "$(ls "$tmp"/root/usr/lib/systemd/system/*.service | wc -l)" = 5 ] || fail "not the 5 units"

dpkg-deb -e "$deb" "$tmp/control"
for s in postinst prerm postrm; do
  [ -x "$tmp/control/$s" ] && sh -n "$tmp/control/$s" || fail "maintainer script $s missing or not valid sh"
done
grep -q "adduser --system" "$tmp/control/postinst" || fail "postinst makes no system user"
grep -q "/usr/bin/gpilot-keygen /etc/gesture-pilot/bus.key" "$tmp/control/postinst" || fail "postinst: the bus key"
depends="$(dpkg-deb -f "$deb" Depends)"
for p in liblcm1 libopencv-core406 libyaml-cpp0.7 libturbojpeg0 libsystemd0 \
         $(grep -oE '^[a-z0-9][^ #]*' "$src/deploy/runtime-packages"); do
  [[ ", $depends," == *", $p"[\ ,]* ]] || fail "Depends lacks $p: $depends"
done

# The maintainer scripts, run as dpkg would (root only), against a private copy of /etc bound over /etc in a
# mount namespace (the host's users and /etc stay untouched), with the unpacked binaries and data in place of
# /usr's: the user (in group video), config.yaml = default.yaml, a 0600 bus key a stage running as the user
# loads; a second configure (upgrade) keeps them; purge removes /etc/gesture-pilot.
if [ "$(id -u)" = 0 ] && unshare -m true 2> /dev/null; then
  sed -e "s|/usr/bin/|$tmp/root/usr/bin/|g" -e "s|/usr/share/gesture-pilot|$tmp/root/usr/share/gesture-pilot|g" \
    "$tmp/control/postinst" > "$tmp/postinst"
  chmod +x "$tmp/postinst"
  chmod 755 "$tmp"  # mktemp -d is 0700: the stage below runs as gesture-pilot
  cp -a /etc "$tmp/etc"
  unshare -m bash -euc '
    tmp=$1; mount --bind "$tmp/etc" /etc
    fail() { echo "test_deb: FAIL: $*" >&2; exit 1; }
    "$tmp/postinst" configure || fail "postinst configure"
    key_before=$(cat /etc/gesture-pilot/bus.key)
    "$tmp/postinst" configure || fail "postinst configure (upgrade)"
    [ "$(cat /etc/gesture-pilot/bus.key)" = "$key_before" ] || fail "an upgrade changed the bus key"
    getent passwd gesture-pilot > /dev/null || fail "no user gesture-pilot"
    id -nG gesture-pilot | grep -qw video || fail "gesture-pilot is not in group video"
    cmp -s /etc/gesture-pilot/config.yaml "$tmp/root/usr/share/gesture-pilot/deploy/config/default.yaml" \
      || fail "config.yaml is not default.yaml"
    [ "$(stat -c "%a %U" /etc/gesture-pilot/bus.key)" = "600 gesture-pilot" ] || fail "bus.key: $(stat -c "%a %U" /etc/gesture-pilot/bus.key)"
    # a stage as the units run it (user, key, config) starts; stopped by SIGTERM after 2 s (124) it was running
    rc=0
    timeout 2 setpriv --reuid gesture-pilot --regid gesture-pilot --init-groups env GPILOT_BUS_KEY=/etc/gesture-pilot/bus.key \
      "$tmp/root/usr/bin/gpilot-decide" --config /etc/gesture-pilot/config.yaml --lcm-url memq:// > "$tmp/decide.log" 2>&1 || rc=$?
    [ "$rc" = 124 ] || { cat "$tmp/decide.log" >&2; fail "gpilot-decide as gesture-pilot with the key exited $rc"; }
    "$tmp/control/prerm" remove && "$tmp/control/postrm" remove || fail "prerm/postrm remove"
    [ -f /etc/gesture-pilot/bus.key ] || fail "remove (not purge) deleted the bus key"
    "$tmp/control/postrm" purge || fail "postrm purge"
    [ ! -e /etc/gesture-pilot ] || fail "purge left /etc/gesture-pilot"
  ' test_deb "$tmp" || exit 1
else
  echo "test_deb: maintainer scripts not run (needs root and a mount namespace)" >&2
fi

# The packaged (stripped) binaries run from the unpacked tree and find their data beside them.
(cd "$tmp" && GPILOT_ROOT= "$tmp/root/usr/bin/gpilot-eval-hands" --scenario tour --stride 50 --png-dir '' --json \
   2> /dev/null) > "$tmp/eval.json" || fail "the packaged gpilot-eval-hands"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["frames"] == 30 and d["kind_accuracy"] > 0.9, d' \
  "$tmp/eval.json" || fail "the packaged gpilot-eval-hands' answer"
echo "test_deb: OK: $(basename "$deb"), $(wc -l < "$tmp/contents") entries, $(du -k "$deb" | cut -f1) kB" >&2
