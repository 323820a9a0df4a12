#!/usr/bin/env bash
# The Debian package, as a user meets it: cpack builds it, apt installs it with what it depends
# on, the installed /usr/bin/tumble renders the default scene from an unrelated folder (no file
# of the source tree needed), man finds tumble(1), the bash completion sources cleanly, lintian
# finds no error; then the package and whatever apt pulled in for it are purged, and the list of
# installed packages must be the one found at the start.
#   deb_install_test.sh BUILD_DIR
# Needs root (it installs a package; CI runs as root): otherwise exit 77, which CTest reports
# as skipped. Refuses to run where tumble is already installed rather than replace it.
set -euo pipefail
build=$(realpath "$1")
export DEBIAN_FRONTEND=noninteractive
apt_get=(apt-get -y -q -o DPkg::Lock::Timeout=300)

if [ "$(id -u)" -ne 0 ]; then
  echo "SKIPPED: the package test installs and removes a Debian package, so it needs root (CI runs as root)"
  exit 77
fi
# One package test at a time on a machine: two would install and purge the same package.
exec 9>/var/lock/tumble-package-test.lock
flock -w 600 9

step_start=$SECONDS
step() { echo "== $1 (at ${SECONDS}s)"; }
if dpkg-query -W -f='${Status}' tumble 2>/dev/null | grep -q "ok installed"; then
  echo "FAIL: tumble $(dpkg-query -W -f='${Version}' tumble) is already installed; this test would" \
       "replace and then purge it. Remove it first (apt-get purge tumble)." >&2
  exit 1
fi
if [ -e /usr/bin/tumble ]; then
  echo "FAIL: /usr/bin/tumble exists but belongs to no package; this test would overwrite it" >&2
  exit 1
fi
installed() { dpkg-query -W -f='${binary:Package} ${db:Status-Abbrev}\n' | awk '$2 ~ /^ii/ {print $1}' | sort; }
before=$(installed)

work=$(mktemp -d)
chmod 755 "$work"  # apt reads the .deb as its unprivileged _apt user
purge() {
  if dpkg-query -W -f='${Status}' tumble 2>/dev/null | grep -q installed; then
    "${apt_get[@]}" purge tumble >/dev/null
  fi
  # What apt pulled in for tumble, and only that: the packages not installed at the start.
  local pulled
  pulled=$(comm -13 <(echo "$before") <(installed) | tr '\n' ' ')
  if [ -n "${pulled// /}" ]; then
    echo "purging what tumble pulled in: $pulled"
    # shellcheck disable=SC2086
    "${apt_get[@]}" purge $pulled >/dev/null
  fi
  rm -rf "$work"
}
trap purge EXIT

step "cpack"
(cd "$work" && cpack --config "$build/CPackConfig.cmake" -B "$work" >cpack.log) || {
  cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/tumble_*.deb)
echo "$(basename "$deb"): $(stat -c %s "$deb") bytes"
dpkg-deb -f "$deb" Depends

step "lintian"
lintian_log=$(lintian --fail-on error "$deb" 2>&1) || {
  echo "$lintian_log"; echo "FAIL: lintian reports errors" >&2; exit 1; }
lintian_log=$(grep -v "running with root privileges" <<<"$lintian_log" || true)
echo "${lintian_log:-lintian: no errors, no warnings}"

step "apt-get install"
install_start=$SECONDS
"${apt_get[@]}" install "$deb" >"$work/apt.log" || { cat "$work/apt.log"; exit 1; }
echo "installed in $((SECONDS - install_start)) s"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
for f in /usr/bin/tumble /usr/share/doc/tumble/copyright /usr/share/doc/tumble/changelog.gz \
         /usr/share/doc/tumble/scene.md /usr/share/doc/tumble/examples/scenes/default.toml \
         /usr/share/bash-completion/completions/tumble /usr/share/zsh/vendor-completions/_tumble; do
  [ -f "$f" ] || fail "$f is not installed"
done

step "the installed tumble, from another folder"
mkdir "$work/run"
version=$(cd "$work/run" && env -i PATH=/usr/bin:/bin /usr/bin/tumble --version | head -n 1)
[ "$version" = "tumble $(dpkg-deb -f "$deb" Version)" ] || fail "tumble --version says '$version'"
(cd "$work/run" && env -i PATH=/usr/bin:/bin HOME="$work/run" \
  tumble render --size 160x120 --duration 0.5 --quiet) || fail "tumble render exited with $?"
clip=$work/run/out/default/clip.mp4
if [ -s "$clip" ]; then
  frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
           -of csv=p=0 "$clip")
  # 0.5 s at the default scene's 60 fps: exactly 30 frames (SPEC: N = round(duration * fps)).
  [ "$frames" = 30 ] || fail "clip.mp4 has $frames frames, not 30"
else
  fail "no clip.mp4 in $work/run/out/default"
fi

step "man -w tumble"
excludes=$(grep -ls '^path-exclude.*/usr/share/man' /etc/dpkg/dpkg.cfg.d/* 2>/dev/null || true)
if [ -n "$excludes" ]; then
  fail "dpkg on this machine drops /usr/share/man when installing ($excludes): the package" \
       "contains the page ($(dpkg-deb -c "$deb" | grep -o 'usr/share/man/.*')) but man cannot" \
       "find it here; remove that path-exclude to check it"
elif page=$(man -w tumble 2>&1); then
  [ "$page" = /usr/share/man/man1/tumble.1.gz ] || fail "man -w tumble finds $page"
  MANWIDTH=120 man tumble 2>/dev/null | grep -q "tumble render" || fail "man tumble does not show 'tumble render'"
else
  fail "man -w tumble: $page"
fi

step "bash completion"
errors=$(bash --norc --noprofile -c 'source /usr/share/bash-completion/completions/tumble &&
  complete -p tumble' 2>&1 >/dev/null) || fail "the bash completion does not source: $errors"
[ -z "$errors" ] || fail "sourcing the bash completion prints: $errors"

step "apt-get purge"
trap - EXIT
purge
[ ! -e /usr/bin/tumble ] || fail "/usr/bin/tumble is still there after the purge"
[ "$(installed)" = "$before" ] || fail "installed packages differ from the start: $(diff <(echo "$before") <(installed) | tr '\n' ' ')"

if [ "$failures" -gt 0 ]; then
  echo "$failures problem(s)" >&2
  exit 1
fi
echo "package test passed in $((SECONDS - step_start)) s"
