#!/usr/bin/env bash
# The release's Python wheels, installed and tested where this machine can run them:
# manylinux2014 x86_64 natively, manylinux2014 aarch64 under qemu-user with Debian's
# arm64 CPython. (No Windows or macOS Python can be had here: scripts/check-dist.py
# checks those wheels' libraries against the header instead.)
#   scripts/test-release-python.sh REL      (REL: dist/orient-VERSION)
set -euo pipefail
cd "$(dirname "$0")/.."
py="$1/python"
cargo build --quiet -p orient-tools --bin replay
for arch in x86_64 aarch64; do
  start=$SECONDS
  wheel=$(ls "$py"/orient_imu-*-py3-none-manylinux2014_"$arch".*.whl)
  if [ "$arch" = x86_64 ]; then
    scripts/test-wheel.sh "$wheel"
  else
    scripts/test-wheel-qemu.sh "$wheel"
  fi
  echo "ok   $(basename "$wheel"): $((SECONDS - start)) s"
done
