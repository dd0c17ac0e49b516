#!/usr/bin/env bash
# Installs dependencies (Debian 12 packages) and builds dynrad in ./build (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="${DYNRAD_BUILD_TYPE:-Release}" > build-configure.log || {
  cat build-configure.log
  exit 1
}
rm -f build-configure.log
cmake --build build --parallel "$(nproc)"
