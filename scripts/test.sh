#!/usr/bin/env bash
# README's second command: build, then run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh all  # the tests too, and every package they need
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
