#!/usr/bin/env bash
# run.sh — the sea round a real coastline (GSHHG, through Debian's GMT), graded toward the shore,
# meshed by meshd (meshctl against a local meshd) and by Gmsh from the same polygons, at the same
# node count; prints a Markdown table.
#
#   bench/coastline/run.sh [--backend cpu|gpu] [--repeat R] [--no-gmsh] [PREFIX]
#
# PREFIX (default $WORK/archipelago) names the region's files:
#   PREFIX.geojson .env .islands   the land and the clip box (make_region.py; needs gmt and the
#                                  gmt-gshhg-full package, which this script installs if absent)
#   PREFIX.textproto .geo          the sea as meshd's request and as Gmsh's geometry
#                                  (export_ocean.py; needs python3-gdal)
# Missing files are made; existing ones are used as they are. So on a machine with only meshd,
# meshctl, python3 with numpy and the PREFIX.textproto and PREFIX.islands copied in (no GMT, GDAL,
# Gmsh or network), `run.sh --backend gpu --no-gmsh PREFIX` meshes and checks the same request.
#
# Steps: 1. make what is missing; 2. start meshd --backend B on a free port; 3. mesh R times with
# meshctl (time = meshd's own "mesh" seconds: the engine, without transfer and file writing;
# median of R); 4. check the last mesh (check_mesh.py: valid, q_min, q_mean, islands of at least
# MIN_ISLAND m2 kept, triangles on land); 5. Gmsh (Frontal-Delaunay, the default, and Delaunay) on PREFIX.geo with
# its size field scaled until its node count is within 2% of meshd's, timed R times (process wall
# time, median), checked the same way; 6. the table.
#
# Environment (defaults in brackets): WORK [bench/coastline/data], REGION [19.3/23.2/59.5/60.8:
# the Archipelago Sea and Åland], H0 [200] metres, SIMPLIFY [1] and OPEN [1] times H0 (see
# export_ocean.py), GRADE [1,0.00025,8], FEATURE [3,0.25,8] (K,H_MIN,H_MAX; "" for none),
# GRADATION [0.1; 0 for none], MIN_ISLAND [(2 H0)^2] m2 (also the smallest pocket of sea kept),
# MESHD [build/bin/meshd], MESHCTL [build/bin/meshctl], GMSH [gmsh], PYTHON [/usr/bin/python3].
set -euo pipefail
shopt -s inherit_errexit

here=$(cd "$(dirname "$0")" && pwd)
backend=cpu repeat=3 gmsh=1
while [[ $# -gt 0 ]]; do
  case $1 in
    --backend) backend=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --no-gmsh) gmsh=0; shift ;;
    -*) echo "run.sh: unknown flag $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
WORK=${WORK:-$here/data}
prefix=${1:-$WORK/archipelago}
REGION=${REGION:-19.3/23.2/59.5/60.8}
H0=${H0:-200} SIMPLIFY=${SIMPLIFY:-1} OPEN=${OPEN:-1} GRADE=${GRADE:-1,0.00025,8}
FEATURE=${FEATURE-3,0.25,8} GRADATION=${GRADATION:-0.1}
MIN_ISLAND=${MIN_ISLAND:-$(awk -v h="$H0" 'BEGIN { print (2 * h) ^ 2 }')}
MESHD=${MESHD:-build/bin/meshd} MESHCTL=${MESHCTL:-build/bin/meshctl}
GMSH=${GMSH:-gmsh} PYTHON=${PYTHON:-/usr/bin/python3}
mkdir -p "$(dirname "$prefix")"
log() { echo "run.sh: $*" >&2; }

# ---- 1. the region -----------------------------------------------------------------------------

if [[ ! -f $prefix.textproto || ! -f $prefix.islands ]]; then
  if [[ ! -f $prefix.geojson ]]; then
    if ! dpkg-query -W -f='${Status}' gmt gmt-gshhg-full 2>/dev/null | grep -q "install ok"; then
      log "installing gmt gmt-gshhg-full (GSHHG full resolution, about 50 MB)"
      sudo=""; [[ $(id -u) -eq 0 ]] || sudo=sudo
      DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        gmt gmt-gshhg-full python3-gdal >&2
    fi
    "$PYTHON" "$here/make_region.py" --region "$REGION" --resolution f "$prefix" >&2
  fi
  # shellcheck disable=SC1090
  . "$prefix.env"
  "$PYTHON" "$here/export_ocean.py" "$prefix.geojson" --to-crs "$TO_CRS" --clip "$CLIP" \
    --h0 "$H0" --simplify "$SIMPLIFY" --open "$OPEN" --min-pocket "$MIN_ISLAND" --grade "$GRADE" \
    ${FEATURE:+--feature "$FEATURE"} --gradation "$GRADATION" "$prefix" >&2
fi

# ---- 2. meshd ----------------------------------------------------------------------------------

[[ -x $MESHD && -x $MESHCTL ]] || { log "$MESHD or $MESHCTL not built"; exit 1; }
tmp=$(mktemp -d)
# shellcheck source=bench/coastline/local_meshd.sh
. "$here/local_meshd.sh"
meshd_pid=
trap 'kill $meshd_pid 2>/dev/null; wait $meshd_pid 2>/dev/null; rm -rf "$tmp"' EXIT
start_local_meshd "$MESHD" "$MESHCTL" "$tmp/meshd.log" --backend "$backend" --max-nodes 20000000 ||
  { cat "$tmp/meshd.log" >&2; log "meshd did not start"; exit 1; }
server=(--server "127.0.0.1:$port" --deadline 7200)

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
check() {  # check MSH22 [--orient]: check_mesh.py's key=value line, or "checked=no" without numpy
  if "$PYTHON" -c "import numpy" 2>/dev/null; then
    "$PYTHON" "$here/check_mesh.py" "$@" --request "$prefix.textproto" "$prefix.islands" \
      "$MIN_ISLAND" || true
  else
    echo "checked=no"
  fi
}
field() { tr ' ' '\n' <<<"$2" | sed -n "s/^$1=//p"; }

# ---- 3-4. meshd --------------------------------------------------------------------------------

times=()
for rep in $(seq "$repeat"); do
  out=$("$MESHCTL" "${server[@]}" generate "$prefix.textproto" --backend "$backend" \
    -o "$tmp/meshd.msh22" 2>"$tmp/meshctl.err") || { cat "$tmp/meshctl.err" >&2; exit 1; }
  t=$(sed -n 's/.*(mesh \([0-9.]*\) s.*/\1/p' <<<"$out")
  device=$(sed -n 's/.* done on \(.*\)$/\1/p' <<<"$out")
  log "meshd run $rep on $device: $(tr '\n' ' ' <<<"$out")"
  times+=("$t")
done
meshd_t=$(printf '%s\n' "${times[@]}" | median)
meshd_check=$(check "$tmp/meshd.msh22")
log "meshd: $meshd_check"
nodes=$(field nodes "$meshd_check")
[[ -n $nodes ]] || nodes=$(sed -n 's/.*nodes \([0-9]*\) .*/\1/p' <<<"$out")

rows=("$(printf '| meshd %s (%s) | %s | %s | %s | %s | %s | %s | %s |' "$backend" "$device" \
  "$nodes" "$(field triangles "$meshd_check")" "$meshd_t" "$(field q_min "$meshd_check")" \
  "$(field q_mean "$meshd_check")" "$(field islands "$meshd_check")" \
  "$(field on_land "$meshd_check")")")

# ---- 5. Gmsh -----------------------------------------------------------------------------------

run_gmsh() {  # run_gmsh ALGO HS: meshes once; prints "<wall s> <nodes>"
  local start end
  start=$(date +%s.%N)
  "$GMSH" -2 -setnumber hs "$2" -setnumber algo "$1" -format msh22 "$prefix.geo" \
    -o "$tmp/gmsh.msh22" >"$tmp/gmsh.log" 2>&1 || { tail -5 "$tmp/gmsh.log" >&2; return 1; }
  end=$(date +%s.%N)
  echo "$(echo "$end - $start" | bc -l) $(awk '/^\$Nodes/ { getline; print; exit }' "$tmp/gmsh.msh22")"
}
if [[ $gmsh == 1 ]]; then
  command -v "$GMSH" >/dev/null || { log "$GMSH not found (or give --no-gmsh)"; exit 1; }
  for algo in 6 5; do
    name=$([[ $algo == 6 ]] && echo "Frontal-Delaunay (default)" || echo "Delaunay")
    hs=1
    for _ in 1 2 3 4 5 6; do  # the node count goes as 1 / hs^2
      if ! read -r _ gnodes < <(run_gmsh "$algo" "$hs"); then
        # Gmsh sometimes cannot recover a boundary edge between two close curves at one size;
        # a slightly different size meshes them.
        log "gmsh $name hs=$hs failed; trying hs=$hs * 0.98"
        hs=$(echo "$hs * 0.98" | bc -l)
        continue
      fi
      log "gmsh $name hs=$hs: $gnodes nodes (meshd $nodes)"
      off=$(echo "($gnodes - $nodes) / $nodes" | bc -l)
      [[ $(echo "$off < 0.02 && $off > -0.02" | bc -l) == 1 ]] && break
      hs=$(echo "$hs * sqrt($gnodes / $nodes)" | bc -l)
    done
    gtimes=()
    for rep in $(seq "$repeat"); do
      read -r t gnodes < <(run_gmsh "$algo" "$hs") || { log "gmsh $name failed at hs=$hs"; break; }
      log "gmsh $name run $rep: $t s, $gnodes nodes"
      gtimes+=("$t")
    done
    if [[ ${#gtimes[@]} -lt $repeat ]]; then
      rows+=("| Gmsh $("$GMSH" --version 2>&1) $name | failed (see the log) | | | | | | |")
      continue
    fi
    g=$(check "$tmp/gmsh.msh22" --orient)
    log "gmsh $name: $g"
    rows+=("$(printf '| Gmsh %s %s | %s | %s | %.3f | %s | %s | %s | %s |' \
      "$("$GMSH" --version 2>&1)" "$name" "$(field nodes "$g")" "$(field triangles "$g")" \
      "$(printf '%s\n' "${gtimes[@]}" | median)" "$(field q_min "$g")" "$(field q_mean "$g")" \
      "$(field islands "$g")" "$(field on_land "$g")")")
  done
fi

# ---- 6. the table ------------------------------------------------------------------------------

echo "Region $prefix: h0 $H0 m, simplify $SIMPLIFY h0, open $OPEN h0, grade $GRADE," \
  "feature ${FEATURE:-none}, gradation $GRADATION (Gmsh: the grade alone, at meshd's node count);" \
  "islands counted from $MIN_ISLAND m2; $(nproc) CPUs, load at end $(cut -d' ' -f1-3 /proc/loadavg);" \
  "time: meshd's mesh seconds / Gmsh's process wall time, median of $repeat."
echo
echo "| mesher | nodes | triangles | time s | q_min | q_mean | islands kept | triangles on land |"
echo "|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
