#!/usr/bin/env bash
# Assembles the Unity package (UPM) com.orient.filters into OUT_DIR:
#   scripts/package-unity.sh OUT_DIR [LIB_ROOT]
# from bindings/unity, bindings/csharp, the licences and changelog, and, when LIB_ROOT
# (a release's lib/ folder from scripts/release.sh) is given, the native plugins:
#   Plugins/Windows/x86_64/orient.dll        Editor (Windows) and Windows player, x86_64
#   Plugins/macOS/liborient.dylib            Editor (macOS) and macOS player, universal
#   Plugins/Linux/x86_64/liborient.so        Editor (Linux) and Linux player, x86_64
#   Plugins/Android/arm64-v8a/liborient.a    Android (Quest) ARM64, IL2CPP links it
#   Plugins/Android/armeabi-v7a/liborient.a  Android ARMv7, IL2CPP links it
#   Plugins/iOS/liborient.a                  iOS, linked into the app by Xcode
# Every file and folder gets a .meta (Unity ignores assets without one in an immutable
# package); each GUID is derived from the asset's path in the package, so it is the same
# on every run and differs between assets. Plugin .meta files hold the import settings
# (PluginImporter) that enable exactly one platform and CPU.
# URLs in package.json come from ORIENT_REPOSITORY_URL (see scripts/release.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:?usage: $0 OUT_DIR [LIB_ROOT]}"
libs="${2:-}"
pkg="$out/com.orient.filters"
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
repo="${ORIENT_REPOSITORY_URL:-}"
if [ -z "$repo" ]; then
  repo=$(sed -n 's/^repository = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
fi
rm -rf "$pkg"
mkdir -p "$pkg/Runtime"
cp bindings/unity/README.md "$pkg/README.md"
cp CHANGELOG.md "$pkg/CHANGELOG.md"
cat LICENSE-MIT >"$pkg/LICENSE.md"
printf '\n---\n\n' >>"$pkg/LICENSE.md"
cat LICENSE-APACHE >>"$pkg/LICENSE.md"
cp bindings/unity/Runtime/* "$pkg/Runtime/"
cp bindings/csharp/Orient.Native.cs bindings/csharp/Orient.cs "$pkg/Runtime/"
cp -r "bindings/unity/Samples~" "$pkg/"
if [ -z "$repo" ]; then
  # No repository URL is recorded yet: the package.json links use a reserved placeholder
  # host until Cargo.toml's `repository` (or ORIENT_REPOSITORY_URL) names the real one.
  echo "package-unity.sh: no repository URL (Cargo.toml repository / ORIENT_REPOSITORY_URL); package.json links use https://example.invalid/orient" >&2
fi
base="${repo:-https://example.invalid/orient}"
sed -e "s|@VERSION@|$version|g" -e "s|@REPOSITORY@|$base|g" bindings/unity/package.json.in >"$pkg/package.json"

guid() { printf 'com.orient.filters/%s' "$1" | md5sum | cut -c1-32; }

# plugin REL_PATH SOURCE EDITOR_OS EDITOR_CPU PLAYER_KEY PLAYER_CPU
plugin() {
  local rel=$1 src=$2 eos=$3 ecpu=$4 player=$5 pcpu=$6
  [ -f "$src" ] || return 0
  mkdir -p "$pkg/$(dirname "$rel")"
  cp "$src" "$pkg/$rel"
  local editor=0 win=0 osx=0 linux=0 android=0 ios=0
  [ -n "$eos" ] && editor=1
  case $player in
    "Standalone: Win64") win=1 ;;
    "Standalone: OSXUniversal") osx=1 ;;
    "Standalone: Linux64") linux=1 ;;
    "Android: Android") android=1 ;;
    "iPhone: iOS") ios=1 ;;
  esac
  cpu() { if [ "$1" = 1 ]; then echo "$pcpu"; else echo None; fi; }
  {
    echo "fileFormatVersion: 2"
    echo "guid: $(guid "$rel")"
    cat <<EOF
PluginImporter:
  externalObjects: {}
  serializedVersion: 2
  iconMap: {}
  executionOrder: {}
  defineConstraints: []
  isPreloaded: 0
  isOverridable: 0
  isExplicitlyReferenced: 0
  validateReferences: 1
  platformData:
  - first:
      : Any
    second:
      enabled: 0
      settings:
        Exclude Android: $((1 - android))
        Exclude Editor: $((1 - editor))
        Exclude Linux64: $((1 - linux))
        Exclude OSXUniversal: $((1 - osx))
        Exclude Win: 1
        Exclude Win64: $((1 - win))
        Exclude iOS: $((1 - ios))
  - first:
      Android: Android
    second:
      enabled: $android
      settings:
        CPU: $(if [ $android = 1 ]; then echo "$pcpu"; else echo ARMv7; fi)
  - first:
      Any:
    second:
      enabled: 0
      settings: {}
  - first:
      Editor: Editor
    second:
      enabled: $editor
      settings:
        CPU: ${ecpu:-AnyCPU}
        DefaultValueInitialized: true
        OS: ${eos:-AnyOS}
  - first:
      Standalone: Linux64
    second:
      enabled: $linux
      settings:
        CPU: $(cpu $linux)
  - first:
      Standalone: OSXUniversal
    second:
      enabled: $osx
      settings:
        CPU: $(cpu $osx)
  - first:
      Standalone: Win
    second:
      enabled: 0
      settings:
        CPU: None
  - first:
      Standalone: Win64
    second:
      enabled: $win
      settings:
        CPU: $(cpu $win)
  - first:
      iPhone: iOS
    second:
      enabled: $ios
      settings:
        AddToEmbeddedBinaries: false
        CPU: $(if [ $ios = 1 ]; then echo "$pcpu"; else echo AnyCPU; fi)
        CompileFlags:
        FrameworkDependencies:
  userData:
  assetBundleName:
  assetBundleVariant:
EOF
  } >"$pkg/$rel.meta"
}

if [ -n "$libs" ]; then
  plugin Plugins/Windows/x86_64/orient.dll "$libs/windows-x86_64/orient.dll" Windows x86_64 "Standalone: Win64" x86_64
  plugin Plugins/macOS/liborient.dylib "$libs/macos-universal/liborient.dylib" OSX AnyCPU "Standalone: OSXUniversal" AnyCPU
  plugin Plugins/Linux/x86_64/liborient.so "$(ls "$libs"/linux-x86_64/liborient.so.*.*.* 2>/dev/null | head -n 1)" Linux x86_64 "Standalone: Linux64" x86_64
  plugin Plugins/Android/arm64-v8a/liborient.a "$libs/android-arm64-v8a/liborient.a" "" "" "Android: Android" ARM64
  plugin Plugins/Android/armeabi-v7a/liborient.a "$libs/android-armeabi-v7a/liborient.a" "" "" "Android: Android" ARMv7
  plugin Plugins/iOS/liborient.a "$libs/ios-arm64/liborient.a" "" "" "iPhone: iOS" ARM64
fi

# A .meta for every other file and folder. Samples~ itself gets none (Unity imports no
# folder whose name ends in ~); its files do, so an imported sample keeps stable GUIDs.
importer() {
  case "$1" in
    *.cs) printf 'MonoImporter:\n  externalObjects: {}\n  serializedVersion: 2\n  defaultReferences: []\n  executionOrder: 0\n  icon: {instanceID: 0}\n  userData:\n  assetBundleName:\n  assetBundleVariant:\n' ;;
    *.asmdef) printf 'AssemblyDefinitionImporter:\n  externalObjects: {}\n  userData:\n  assetBundleName:\n  assetBundleVariant:\n' ;;
    package.json) printf 'PackageManifestImporter:\n  externalObjects: {}\n  userData:\n  assetBundleName:\n  assetBundleVariant:\n' ;;
    *.md | *.txt | *.csv | *.json) printf 'TextScriptImporter:\n  externalObjects: {}\n  userData:\n  assetBundleName:\n  assetBundleVariant:\n' ;;
    *) printf 'DefaultImporter:\n  externalObjects: {}\n  userData:\n  assetBundleName:\n  assetBundleVariant:\n' ;;
  esac
}
(cd "$pkg" && find . -mindepth 1 ! -name '*.meta' ! -name '*~' | sed 's|^\./||' | LC_ALL=C sort) | while read -r rel; do
  [ -f "$pkg/$rel.meta" ] && continue
  {
    echo "fileFormatVersion: 2"
    echo "guid: $(guid "$rel")"
    if [ -d "$pkg/$rel" ]; then
      echo "folderAsset: yes"
      importer folder
    else
      importer "$(basename "$rel")"
    fi
  } >"$pkg/$rel.meta"
done
echo "Unity package in $pkg"
