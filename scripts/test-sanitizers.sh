#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer: builds the
# test program and the dynrad command line it runs (gcc, -O1, assertions on) into
# build-asan, then runs every test with ctest. The first sanitizer error fails its test
# (halt_on_error; the dynrad processes the tests start inherit the same options).
#
# Embree and oneTBB are uninstrumented system libraries; the only allowance for them is
# tests/lsan.supp (memory they keep until exit), nothing else is switched off.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DDYNRAD_SANITIZE=ON -DDYNRAD_BUILD_BENCH=OFF > build-asan-configure.log || {
  cat build-asan-configure.log
  exit 1
}
rm -f build-asan-configure.log
cmake --build build-asan --parallel "$(nproc)" --target dynrad dynrad_tests

export ASAN_OPTIONS=halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)" --timeout 1500
