#!/usr/bin/env bash
# README's two commands, as they must stay (issue 20, "the first run"):
#   1. scripts/setup (build and run packages only), the `tumble` preset, the binary alone, a render;
#   2. scripts/setup --tests, the release preset, every test; and .ci/run runs command 2 exactly.
# The `tumble` preset is configured for real (in a scratch folder): it must make the tumble target
# and none of the tests, benchmarks or packaging, and its build preset must build only tumble.
#   readme_commands.sh SOURCE_DIR
set -euo pipefail
src=$(realpath "$1")
fail() { echo "FAIL: $*" >&2; exit 1; }

commands=$(awk '/^```sh$/ { inside = 1; next } /^```$/ { if (inside) exit } inside' "$src/README.md")
first=$(sed -n 1p <<< "$commands")
second=$(sed -n 2p <<< "$commands")
[ "$first" = "scripts/setup && cmake --preset tumble && cmake --build --preset tumble && ./build/release/tumble render" ] ||
  fail "README command 1 is: $first"
[[ "$second" == "scripts/setup --tests && cmake --preset release && cmake --build --preset release && ctest --preset release" ]] ||
  fail "README command 2 is: $second"
grep -qxF "$second" "$src/.ci/run" || fail ".ci/run does not run README command 2 exactly"

# scripts/setup: the test packages only with --tests.
grep -q 'test_packages=(' "$src/scripts/setup" || fail "scripts/setup has no test package list"
for p in libgtest-dev chromium slurmd lintian zsh clang; do
  sed -n '/^packages=(/,/^)/p' "$src/scripts/setup" | grep -qw "$p" &&
    fail "scripts/setup installs the test package $p by default"
  sed -n '/^test_packages=(/,/^)/p' "$src/scripts/setup" | grep -qw "$p" ||
    fail "scripts/setup --tests does not install $p"
done

# The tumble preset, configured: the binary, no tests, benchmarks or packaging.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$src" && cmake --preset tumble -B "$work/build" > "$work/configure.log") ||
  fail "cmake --preset tumble failed: $(cat "$work/configure.log")"
targets=$(ninja -C "$work/build" -t targets all | cut -d: -f1)
grep -qx "tumble" <<< "$targets" || fail "the tumble preset has no tumble target"
for t in e2e_tests unit_sim_tests bench/bench_step tumble_man_page; do
  grep -qx "$t" <<< "$targets" && fail "the tumble preset configures $t"
done
python3 - "$src/CMakePresets.json" <<'PY' || fail "the tumble build preset does not build only tumble"
import json, sys
presets = {p["name"]: p for p in json.load(open(sys.argv[1]))["buildPresets"]}
sys.exit(0 if presets["tumble"].get("targets") == ["tumble"] else 1)
PY
echo "README commands: 1 builds the binary alone, 2 (run by .ci/run) everything"
