#!/usr/bin/env bash
# Assembles the Unity package (UPM) com.orient.filters into OUT_DIR from
# bindings/unity, bindings/csharp and the native libraries built so far:
#   scripts/package-unity.sh OUT_DIR
# Plugins/x86_64/liborient.so comes from target/release (cargo build --release);
# Android libraries from target/aarch64-linux-android and target/armv7-linux-androideabi
# when present. Other platforms' libraries are added by hand (bindings/unity/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:?usage: $0 OUT_DIR}"
pkg="$out/com.orient.filters"
rm -rf "$pkg"
mkdir -p "$pkg/Runtime" "$pkg/Plugins/x86_64"
cp bindings/unity/package.json bindings/unity/README.md "$pkg/"
cp bindings/unity/Runtime/* "$pkg/Runtime/"
cp bindings/csharp/Orient.Native.cs bindings/csharp/Orient.cs "$pkg/Runtime/"
cp -r "bindings/unity/Samples~" "$pkg/"
if [ -f target/release/liborient.so ]; then
  cp target/release/liborient.so "$pkg/Plugins/x86_64/liborient.so"
fi
for abi in "aarch64-linux-android:arm64-v8a" "armv7-linux-androideabi:armeabi-v7a"; do
  triple=${abi%%:*} dir=${abi##*:}
  if [ -f "target/$triple/release/liborient.so" ]; then
    mkdir -p "$pkg/Plugins/Android/$dir"
    cp "target/$triple/release/liborient.so" "$pkg/Plugins/Android/$dir/"
  fi
done
echo "Unity package in $pkg"
