#!/usr/bin/env bash
# README's first command: build, then light the bundled Cornell box with dynrad and
# write out/cornell_box.ply (open it in MeshLab) and out/cornell_box.json (the report).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh build  # only what building and running dynrad needs
mkdir -p out
build/plugin/dynrad solve samples/cornell_box.obj -o out/cornell_box.ply --report out/cornell_box.json
echo "Open it with: meshlab out/cornell_box.ply"
