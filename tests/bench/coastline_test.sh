#!/usr/bin/env bash
# A small real coast end to end (bench/coastline/): GSHHG's high-resolution shoreline of a patch
# of the Norwegian coast west of Bergen (786 shoreline vertices, 63 islands), the sea round it
# graded toward the shore, meshed by meshd through meshctl. Asserts properties only: the mesh is
# valid, every island of at least (2 h0)^2 is a hole in it and no triangle lies on land
# (check_mesh.py exits 1 otherwise).
# q_min and q_mean are printed, not asserted (bench/RESULTS.md follows them, coastline section).
# Skips (77) where gmt, its gmt-gshhg-high data or python3-gdal is missing.
#
#   coastline_test.sh MESHD MESHCTL SOURCE_DIR WORK_DIR
set -euo pipefail
meshd=$1 meshctl=$2 src=$3 work=$4
python=/usr/bin/python3
command -v gmt >/dev/null || { echo "SKIP: gmt not installed (apt-get install gmt)"; exit 77; }
[[ -f /usr/share/gmt-gshhg/binned_GSHHS_h.nc ]] ||
  { echo "SKIP: GSHHG high resolution missing (apt-get install gmt-gshhg-high)"; exit 77; }
"$python" -c "import osgeo, numpy" 2>/dev/null ||
  { echo "SKIP: $python lacks osgeo or numpy (python3-gdal, python3-numpy)"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
"$python" "$src/bench/coastline/make_region.py" --region 5/5.5/60.2/60.5 --resolution h \
  "$work/region"
# shellcheck disable=SC1091
. "$work/region.env"
"$python" "$src/bench/coastline/export_ocean.py" "$work/region.geojson" --to-crs "$TO_CRS" \
  --clip "$CLIP" --h0 250 --simplify 1 --open 1 --min-pocket 250000 --grade 1,0.0005,6 \
  "$work/region"
# shellcheck source=bench/coastline/local_meshd.sh
. "$src/bench/coastline/local_meshd.sh"
meshd_pid=
trap 'kill $meshd_pid 2>/dev/null; wait $meshd_pid 2>/dev/null || true' EXIT
start_local_meshd "$meshd" "$meshctl" "$work/meshd.log" --backend cpu
"$meshctl" --server "127.0.0.1:$port" --deadline 600 generate "$work/region.textproto" \
  -o "$work/sea.msh22"
# The islands file lists all 63; check_mesh.py judges those of at least (2 h0)^2.
result=$("$python" "$src/bench/coastline/check_mesh.py" "$work/sea.msh22" "$work/region.islands" \
  250000 --request "$work/region.textproto")
echo "$result"
grep -q "valid=yes" <<<"$result"
grep -q "on_land=0" <<<"$result"
# Islands must be there to be kept: a region that lost its islands would pass vacuously.
kept=$(sed -n 's/.*islands=\([0-9]*\)\/\([0-9]*\).*/\1 \2/p' <<<"$result")
read -r k n <<<"$kept"
[[ $n -ge 10 && $k -eq $n ]]
