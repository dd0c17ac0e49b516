#!/usr/bin/env bash
# README's first command: build, then light the bundled Cornell box with dynrad and
# write out/cornell_box.ply (open it in MeshLab) and out/cornell_box.json (the report);
# then light the storey sample with its downlights and write its lighting report,
# out/storey_lux.html and out/storey_lux.pdf (EN 12464-1 per room, UGR, the escape route, plans and views), with out/storey_lux.ply;
# a walk-through of the lit storey in the browser, out/storey_walk.html (from
# out/storey_lux.glb); and a room lit by an overcast sky through its windows,
# out/daylight_overcast.html (daylight factors).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh build  # only what building and running dynrad needs
mkdir -p out
build/plugin/dynrad solve samples/cornell_box.obj -o out/cornell_box.ply --report out/cornell_box.json
build/plugin/dynrad solve samples/storey_luminaires.json -o out/storey_lux.ply --html out/storey_lux.html --pdf out/storey_lux.pdf
build/plugin/dynrad solve samples/storey_luminaires.json -o out/storey_lux.glb
build/plugin/dynrad view out/storey_lux.glb -o out/storey_walk.html --title "Storey with downlights"
build/plugin/dynrad solve samples/daylight_overcast.json -o out/daylight_overcast.ply --html out/daylight_overcast.html
echo "Open it with: meshlab out/cornell_box.ply"
echo "The storey's lighting report: out/storey_lux.html and out/storey_lux.pdf; a daylit room's: out/daylight_overcast.html (web browser)"
echo "Walk through the lit storey: out/storey_walk.html (web browser)"
