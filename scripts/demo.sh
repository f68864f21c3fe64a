#!/usr/bin/env bash
# The main job: builds meshd, meshes every example geometry and writes each mesh as MSH 4.1,
# MSH 2.2, VTU and SVG into out/, with a table of sizes, iterations, times and quality.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/bin/meshbench -o 'out/{name}.msh' -o 'out/{name}.msh22' -o 'out/{name}.vtu' \
  -o 'out/{name}.svg' examples/*.textproto
echo "demo: meshes written to out/ ($(ls out | wc -l) files)"
