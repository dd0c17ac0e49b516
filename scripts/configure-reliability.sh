#!/usr/bin/env bash
# Configures build-fuzz, the one build directory of the reliability checks
# (scripts/test-sanitizers.sh and scripts/fuzz.sh): clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, libFuzzer's coverage (DYNRAD_FUZZ), the tests and the fuzz
# targets. Debug keeps assertions (internal invariants) on; -O1 keeps the build and the
# runs fast; line tables are all the debug information the sanitizers' reports need
# (file and line in every frame; full -g made solver.cpp compile 25% slower). Configuring again with the same options changes nothing, so the two scripts
# share every object file.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-fuzz -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" -DDYNRAD_FUZZ=ON \
  -DDYNRAD_BUILD_TESTS=ON -DDYNRAD_BUILD_BENCH=OFF > build-fuzz-configure.log || {
  cat build-fuzz-configure.log
  exit 1
}
rm -f build-fuzz-configure.log
