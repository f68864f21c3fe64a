#!/usr/bin/env bash
# compare_gmsh3d.sh — Gmsh's default 3D mesher (Delaunay, with its optimiser) and meshd's 3D CPU
# engine on the same domains at the same node count, on this machine, in one run: the unit ball
# and the cube [-1,1]^3 minus the ball of radius 0.5 (bench/gmsh3d/<domain>.geo, uniform size
# hs; meshbench3d's domains of the same names).
#
#   bench/compare_gmsh3d.sh [TARGET_NODES...]          (default: 10000 100000)
#   DOMAINS="ball" bench/compare_gmsh3d.sh 1000000
#
# For each domain and target:
#   1. meshes the .geo at a probe size and rescales hs by (nodes / target)^(1/3), up to four
#      times, until gmsh's node count is within 2% of the target;
#   2. times `gmsh -3` (wall time of the whole process; gmsh 4.8's default is one thread);
#   3. measures gmsh's tetrahedra with bench/gmsh3d/tet_quality.py (core/mesh3d's measures);
#   4. runs `meshbench3d --nodes <gmsh's node count>` (its t_total: relaxation and sliver
#      removal, no start-up or file write; threads = MESHD_THREADS or one per hardware thread);
#   5. prints a Markdown table; speed ratio = gmsh time / meshd time.
#
# Environment: GMSH (default gmsh), MESHBENCH3D (default build/bin/meshbench3d), PYTHON (an
# interpreter with meshio; default /usr/bin/python3), MESHD_THREADS, DOMAINS (default
# "ball box_minus_sphere").
set -euo pipefail
shopt -s inherit_errexit

GMSH=${GMSH:-gmsh}
MESHBENCH3D=${MESHBENCH3D:-build/bin/meshbench3d}
PYTHON=${PYTHON:-/usr/bin/python3}
read -r -a domains <<<"${DOMAINS:-ball box_minus_sphere}"
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(10000 100000)
here=$(cd "$(dirname "$0")" && pwd)
threads=()
[[ -n ${MESHD_THREADS:-} ]] && threads=(--threads "$MESHD_THREADS")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# gmsh GEO HS MSH: meshes, prints "seconds nodes".
run_gmsh() {
  local start end log
  start=$(date +%s.%N)
  log=$("$GMSH" -3 -setnumber hs "$2" -format msh22 "$1" -o "$3" 2>&1) || { echo "$log" >&2; return 1; }
  end=$(date +%s.%N)
  echo "$(echo "$end - $start" | bc -l) $(echo "$log" | sed -n 's/^Info *: \([0-9]*\) nodes .*/\1/p' | tail -1)"
}

echo "| domain | target | mesher | nodes | tetrahedra | t s | q_min | q_mean | q < 0.2 | min dihedral | max dihedral | gmsh / meshd time |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for domain in "${domains[@]}"; do
  geo="$here/gmsh3d/$domain.geo"
  for target in "${targets[@]}"; do
    hs=0.1
    for attempt in 1 2 3 4; do
      read -r seconds nodes < <(run_gmsh "$geo" "$hs" "$work/g.msh")
      off=$(echo "($nodes - $target) / $target" | bc -l)
      [[ $(echo "${off#-} < 0.02" | bc -l) == 1 ]] && break
      hs=$(echo "$hs * e(l($nodes / $target) / 3)" | bc -l)
    done
    read -r _ tets qmin qmean low dmin dmax < <("$PYTHON" "$here/gmsh3d/tet_quality.py" "$work/g.msh" | tail -1)
    row=$("$MESHBENCH3D" "${threads[@]}" --nodes "$nodes" "$domain" | grep "^| $domain |")
    IFS='|' read -r _ _ _ _ m_nodes m_tets _ _ _ _ _ m_total m_qmin m_qmean m_low m_dmin m_dmax _ <<<"$row"
    ratio=$(echo "$seconds / $m_total" | bc -l)
    printf '| %s | %s | gmsh | %s | %s | %.2f | %s | %s | %s | %s | %s | |\n' "$domain" "$target" \
      "$nodes" "$tets" "$seconds" "$qmin" "$qmean" "$low" "$dmin" "$dmax"
    printf '| %s | %s | meshd | %s | %s | %.2f | %s | %s | %s | %s | %s | %.2fx |\n' "$domain" \
      "$target" $m_nodes $m_tets $m_total $m_qmin $m_qmean $m_low $m_dmin $m_dmax "$ratio"
  done
done
