#!/usr/bin/env bash
# volume_examples.sh — each request of examples/volumes/ sent once through meshd (one CPU worker,
# threads = MESHD_THREADS or one per hardware thread) by `meshctl generate --json`, and a Markdown
# row per request from its Done event: the job's own time, the quality report, the volume against
# the exact one given here, and how far the surface nodes lie from the boundary (in h0).
#
#   bench/volume_examples.sh [EXAMPLE.textproto...]   (default: examples/volumes/*.textproto)
#
# Environment: MESHD, MESHCTL (default build/bin/...), PORT (default 50071), PYTHON (default
# python3), MESHD_THREADS.
set -euo pipefail
shopt -s inherit_errexit

MESHD=${MESHD:-build/bin/meshd}
MESHCTL=${MESHCTL:-build/bin/meshctl}
PORT=${PORT:-50071}
PYTHON=${PYTHON:-python3}
requests=("$@")
[[ ${#requests[@]} -gt 0 ]] || requests=(examples/volumes/*.textproto)
work=$(mktemp -d)
"$MESHD" --listen "127.0.0.1:$PORT" --backend cpu --cpu-workers 1 \
  --cpu-threads "${MESHD_THREADS:-0}" >"$work/meshd.log" 2>&1 &
meshd_pid=$!
trap 'kill $meshd_pid 2>/dev/null; wait $meshd_pid 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 50); do
  "$MESHCTL" health --server "127.0.0.1:$PORT" >/dev/null 2>&1 && break
  sleep 0.1
done

echo "| request | h0 | nodes | tetrahedra | fixed | iterations | t_mesh s | t_slivers s | q_min | q_mean | min dihedral | max dihedral | q < 0.2 | volume | vs exact | surface off / h0 |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for request in "${requests[@]}"; do
  name=$(basename "$request" .textproto)
  "$MESHCTL" generate "$request" --server "127.0.0.1:$PORT" --json -o "$work/$name.msh" \
    >"$work/$name.json"
  "$PYTHON" - "$name" "$request" "$work/$name.json" <<'PY'
import json, math, re, sys
name, request, events = sys.argv[1], sys.argv[2], sys.argv[3]
# The exact volumes (Pappus for the pulley's cross-section); none known for the others.
exact = {"ball": 4 / 3 * math.pi, "box_minus_sphere": 8 - 4 / 3 * math.pi / 8,
         "graded_cylinder": 2 * math.pi, "torus": 2 * math.pi ** 2 * 1.0 * 0.35 ** 2,
         "pulley": 1.5322}.get(name)
h0 = float(re.search(r"^\s*h0:\s*([0-9.eE+-]+)", open(request).read(), re.M).group(1))
done = [json.loads(l)["done"] for l in open(events) if '"done"' in l][-1]
q, s = done["quality"], done["stats"]
hist = [int(c) for c in q["histogram"]]
vol = q.get("volume", 0.0)
rel = f"{100 * (vol - exact) / exact:+.2f}%" if exact else ""
print(f"| {name} | {h0:g} | {done['nodes']} | {done['tetrahedra']} | {s.get('fixed_nodes', 0)} "
      f"| {s['iterations']} | {s['t_mesh']:.2f} | {s.get('t_slivers', 0):.2f} | {q.get('q_min', 0):.3f} "
      f"| {q['q_mean']:.4f} | {q['min_dihedral_deg']:.1f} | {q['max_dihedral_deg']:.1f} "
      f"| {hist[0] + hist[1]} | {vol:.5g} | {rel} | {q.get('max_surface_offset', 0) / h0:.1e} |")
PY
done
