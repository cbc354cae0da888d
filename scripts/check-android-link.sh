#!/usr/bin/env bash
# Links orient's Android shared library for arm64-v8a and armeabi-v7a with a stand-in
# for the NDK's clang, and checks what build.rs asks of the link: every LOAD segment
# aligned to 16 KB (scripts/check-page-size.py) and the SONAME liborient.so.
# Debian has no Android NDK, so the stand-in is zig's clang for the same architecture,
# linking against empty stub libc/libm/libdl/liblog and an empty libunwind. Like the
# NDK's clang before r28 it passes -z max-page-size=4096 ahead of the caller's flags,
# so a link that does not ask for 16 KB fails here. The result is a link check only,
# never shipped (its stubs record no real dependencies).
#   scripts/check-android-link.sh         (CARGO_TARGET_DIR defaults to target/release-ci)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export PATH="$HOME/.cargo/bin:$PATH"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target/release-ci}"
# CI's lighter profile: release.sh --ci built the dependencies for these targets with it.
export CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=off CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16
zig=("$HOME/.local/orient-tools/bin/python3" -m ziglang)
work="$CARGO_TARGET_DIR/android-link"
mkdir -p "$work"
printf '' >"$work/empty.c"
status=0
for entry in aarch64-linux-android:aarch64-linux-musl armv7-linux-androideabi:arm-linux-musleabihf; do
  IFS=: read -r t zt <<<"$entry"
  stubs="$work/$t"
  mkdir -p "$stubs"
  for l in c m dl log; do
    "${zig[@]}" cc -target "$zt" -nostdlib -shared -Wl,-soname,"lib$l.so" -o "$stubs/lib$l.so" "$work/empty.c"
  done
  rm -f "$stubs/libunwind.a"
  "${zig[@]}" ar rcs "$stubs/libunwind.a"
  cat >"$stubs/clang" <<WRAP
#!/usr/bin/env bash
args=()
for a in "\$@"; do
  case \$a in -march=*|-mcpu=*|-mfpu=*|-mfloat-abi=*|-mthumb*) ;; *) args+=("\$a") ;; esac
done
exec ${zig[*]} cc -target $zt -nostdlib -L"$stubs" -Wl,-z,max-page-size=4096 "\${args[@]}"
WRAP
  chmod +x "$stubs/clang"
  cargo rustc -p orient --release --lib --quiet --target "$t" --crate-type cdylib -- \
    -C linker="$stubs/clang" -C linker-flavor=gcc
  so="$CARGO_TARGET_DIR/$t/release/liborient.so"
  scripts/check-page-size.py "$so" || status=1
  soname=$(readelf -d "$so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
  if [ "$soname" = liborient.so ]; then echo "ok   $t: SONAME liborient.so"; else echo "FAIL $t: SONAME $soname, want liborient.so"; status=1; fi
done
exit "$status"
