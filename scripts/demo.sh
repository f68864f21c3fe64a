#!/usr/bin/env bash
# The main job: builds meshd and meshctl, starts meshd on its embedded defaults (127.0.0.1:50051;
# a GPU worker per visible GPU, the CPU otherwise), meshes every example through it with
# meshctl and writes each mesh as MSH 4.1, MSH 2.2, VTU and SVG (examples/volumes/: tetrahedra,
# the SVG a picture of the surface) into out/, then stops meshd with SIGTERM.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out

build/bin/meshd >out/meshd.log 2>&1 &
meshd_pid=$!
trap 'kill -TERM $meshd_pid 2>/dev/null || true' EXIT
# SERVING once every worker is warm.
for _ in $(seq 100); do
  build/bin/meshctl health --deadline 1 >/dev/null 2>&1 && break
  kill -0 $meshd_pid 2>/dev/null || { cat out/meshd.log; echo "demo: meshd exited" >&2; exit 1; }
  sleep 0.2
done
build/bin/meshctl health

for request in examples/*.textproto; do
  name=$(basename "$request" .textproto)
  build/bin/meshctl generate "$request" \
    -o "out/$name.msh" -o "out/$name.msh22" -o "out/$name.vtu" -o "out/$name.svg"
done

# Volumes (3D): tetrahedra in the same formats, the SVG a picture of the surface.
for request in examples/volumes/*.textproto; do
  name=$(basename "$request" .textproto)
  build/bin/meshctl generate "$request" \
    -o "out/$name.msh" -o "out/$name.msh22" -o "out/$name.vtu" -o "out/$name.svg"
done

kill -TERM $meshd_pid
wait $meshd_pid
trap - EXIT
echo "demo: meshes written to out/ ($(ls out/*.msh out/*.msh22 out/*.vtu out/*.svg | wc -l) files); meshd's log is out/meshd.log"
