#!/usr/bin/env bash
# The Conan recipe (conanfile.py) as a Conan user meets it: `conan create` builds the
# package with cargo and runs test_package, a CMake consumer that finds orient 1 and
# links orient::orient, orient::orient_static and the C++ wrapper, then runs all three.
# Conan (pinned) comes from PyPI through scripts/python-tools.sh; its home is
# target/conan-home, so nothing outside the checkout is touched. cargo builds with CI's
# lighter profile (opt-level 1, no LTO) in target/ci-light, shared with
# scripts/test-python.sh: the dependencies are built once, only orient is compiled here.
# No remote is asked: orient needs no other Conan package.
#   scripts/test-conan.sh
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export PATH="$HOME/.cargo/bin:$PATH"
start=$SECONDS
tools=$(scripts/python-tools.sh)
export CONAN_HOME="$root/target/conan-home"
log="$root/target/conan-create.log"
"$tools/conan" profile detect --exist-ok >"$log" 2>&1
if ! CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=off CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 \
  "$tools/conan" create . --no-remote --build=missing -c user.orient:cargo_target_dir="$root/target/ci-light" >>"$log" 2>&1; then
  cat "$log"
  echo "FAIL conan create" >&2
  exit 1
fi
# The three consumers printed their line (the package's test step fails on a non-zero exit).
n=$(grep -c "q = (" "$log" || true)
[ "$n" = 3 ] || { cat "$log"; echo "FAIL test_package: $n of 3 consumers ran" >&2; exit 1; }
grep -m1 "orient .* (ABI .*) from" "$log" | sed 's/^.*-- /ok   /'
echo "ok   conan create: package built, test_package linked orient::orient, orient::orient_static and orient.hpp and ran them"
echo "conan: $((SECONDS - start)) s"
