#!/usr/bin/env bash
# Builds the host code with sanitizers (no CUDA: compute-sanitizer covers the kernels) and runs
# tests under them:
#   asan  ASan + UBSan (leaks included) over the whole host suite, in build-asan/
#   tsan  TSan over the job queue, the jobs' events and the job manager, in build-tsan/
# Usage: scripts/sanitize.sh [asan] [tsan]   (both by default)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(asan tsan)
for step in "${steps[@]}"; do
  case $step in
    asan)
      cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHD_CUDA=OFF \
        -DMESHD_WERROR=ON -DMESHD_SANITIZE=address,undefined
      cmake --build build-asan -j "$(nproc)"
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
        LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp \
        ctest --test-dir build-asan --output-on-failure -j "$(nproc)" ;;
    tsan)
      # The job queue, the jobs' event streams and the manager with real workers, cancels and
      # retention, from many threads. The gRPC tests are not run under TSan: Debian's gRPC is not
      # instrumented, so every hand-off through its completion queue reads as a race (false
      # positives, one per call); the service keeps its own state under the mutexes tested here.
      cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHD_CUDA=OFF \
        -DMESHD_WERROR=ON -DMESHD_SANITIZE=thread
      cmake --build build-tsan -j "$(nproc)" --target server_jobs_test
      TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/tests/sanitizers/tsan.supp" \
        ctest --test-dir build-tsan --output-on-failure -j "$(nproc)" --repeat until-fail:5 \
        -R '^(JobQueue|JobManager|JobEvents)\.' ;;
    *) echo "sanitize.sh: unknown step $step (asan, tsan)" >&2; exit 2 ;;
  esac
done
