#!/usr/bin/env bash
# Fuzzes the request path (tests/fuzz/request_fuzzer.cpp) for SECONDS (default 60): installs
# clang when missing, builds the fuzzer with libFuzzer, ASan and UBSan into build-fuzz/, runs it
# from the seed corpus (examples/*.textproto and examples/volumes/*.textproto as text and as
# binary, plus the checked-in regression inputs of tests/fuzz/corpus/) and prints executions,
# coverage and findings. Exits non-zero on a finding, whose input lands in
# build-fuzz/fuzz/artifacts/.
#
#   scripts/fuzz.sh [SECONDS]
#
# MESHD_FUZZ_SEED=N fixes libFuzzer's random seed (CI does, so that a run it fails repeats here
# from the same corpus); unset, every run explores differently.
#
# The corpus that libFuzzer grows is kept in build-fuzz/fuzz/corpus/ between runs. Reproduce a
# finding with build-fuzz/bin/request_fuzzer <file>.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
case $seconds in '' | *[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS]" >&2 && exit 2 ;; esac

scripts/install_deps.sh --fuzz
# The compiler is chosen on the first configure only: changing it later would empty the cache.
compilers=()
[ -f build-fuzz/CMakeCache.txt ] ||
  compilers=(-DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${compilers[@]}" \
  -DMESHD_CUDA=OFF -DMESHD_FUZZ=ON >/dev/null
cmake --build build-fuzz --target request_fuzzer -j "$(nproc)"

# Seeds: the first byte selects the format (request_fuzzer.cpp): '0' text, '1' binary.
work=build-fuzz/fuzz
rm -rf "$work/seeds" "$work/artifacts"
mkdir -p "$work/seeds" "$work/corpus" "$work/artifacts"
for f in examples/*.textproto examples/volumes/*.textproto; do
  name=$(basename "$f" .textproto)
  { printf '0'; cat "$f"; } >"$work/seeds/$name.text"
  { printf '1'; protoc --encode=meshd.v1.MeshRequest -I proto meshd/v1/request.proto <"$f"; } \
    >"$work/seeds/$name.binary"
done

# -timeout: seconds per input (a hang is a finding). The slowest valid inputs (the airfoil seed)
# take about 1.5 s alone but passed 10 s on a machine shared by several builds, hence 25.
# -rss_limit_mb also caps single allocations.
# libFuzzer stops itself after -max_total_time, but only once it has replayed the corpus (a few
# thousand inputs take a minute or two): the outer timeout interrupts it at SECONDS + 10, and
# libFuzzer still prints its statistics. Its status 124 is the time limit, not a finding.
log=$work/fuzz.log
status=0
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} timeout --signal=INT --kill-after=30 $((seconds + 10)) \
  build-fuzz/bin/request_fuzzer -max_total_time="$seconds" -seed="${MESHD_FUZZ_SEED:-0}" \
  -max_len=8192 -timeout=25 \
  -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/artifacts/" \
  "$work/corpus" "$work/seeds" tests/fuzz/corpus >"$log" 2>&1 || status=$?

# The summary: libFuzzer's final statistics and its last status line (cov: edges, ft: features).
echo "fuzz: log in $log"
if [ "$status" -eq 124 ]; then
  echo "fuzz: stopped at the time limit (the corpus replay took most of it)"
  status=0
fi
grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' \
  "$log" | sort -u || true
grep -E '^#[0-9]+' "$log" | tail -n 1 || true
# slow-unit-* files are libFuzzer's note of its slowest input (over 10 s), not a finding.
slow=$(find "$work/artifacts" -type f -name 'slow-unit-*' | sort)
[ -n "$slow" ] && echo "fuzz: slowest inputs (under the timeout, not findings):" && echo "$slow"
findings=$(find "$work/artifacts" -type f ! -name 'slow-unit-*' | sort)
if [ -n "$findings" ] || [ "$status" -ne 0 ]; then
  echo "fuzz: FINDINGS (libFuzzer exit status $status):"
  grep -E '^(==[0-9]+==ERROR|SUMMARY)|runtime error|invariant broken|uncaught|terminate' \
    "$log" | head -n 20 || true
  [ -n "$findings" ] && echo "$findings"
  exit 1
fi
echo "fuzz: no findings in ${seconds} s"
