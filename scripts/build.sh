#!/usr/bin/env bash
# Installs dependencies (Debian 12 packages) and builds dynrad in ./build (Release).
#
#   scripts/build.sh build   # dynrad and libdynrad.so only, with only the packages they
#                            # need (scripts/demo.sh)
#   scripts/build.sh [all]   # everything: also the tests and benchmarks, which then must
#                            # configure (scripts/test.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-all}
case $mode in
  build)
    # Tests and benchmarks stay as a previous `all` build configured them (AUTO: built
    # only when their packages are there), but this build does not wait for them.
    settings=(-DDYNRAD_BUILD_TESTS=AUTO -DDYNRAD_BUILD_BENCH=AUTO)
    targets=(--target dynrad dynrad_capi)
    ;;
  all)
    settings=(-DDYNRAD_BUILD_TESTS=ON -DDYNRAD_BUILD_BENCH=ON)
    targets=()
    ;;
  *)
    echo "usage: $0 [build|all]" >&2
    exit 2
    ;;
esac
scripts/install-deps.sh "$mode"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="${DYNRAD_BUILD_TYPE:-Release}" "${settings[@]}" \
  > build-configure.log || {
  cat build-configure.log
  exit 1
}
rm -f build-configure.log
cmake --build build --parallel "$(nproc)" "${targets[@]}"
