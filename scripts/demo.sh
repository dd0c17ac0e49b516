#!/usr/bin/env bash
# README's first command: build, then run dynrad on the bundled Cornell box and write
# out/cornell_box.ply (open it in MeshLab).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/plugin/dynrad info samples/cornell_box.obj
build/plugin/dynrad clean samples/cornell_box.obj -o out/cornell_box.ply
echo "Open it with: meshlab out/cornell_box.ply"
