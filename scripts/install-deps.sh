#!/usr/bin/env bash
# Installs exactly the Debian 12 packages that dynrad's build, tests and CI need.
# clang, libclang-rt-dev (libFuzzer and sanitizer runtimes) and llvm (llvm-symbolizer,
# for readable sanitizer stacks) are for scripts/fuzz.sh and scripts/test-sanitizers.sh.
# Safe to run repeatedly; needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libembree-dev libtbb-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libtinyobjloader-dev libpng-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  meshlab xvfb xauth
  blender
  clang libclang-rt-dev llvm
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install-deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
