#!/usr/bin/env bash
# Builds meshd with warnings as errors and runs the whole test suite (GPU tests skip where no GPU
# is visible).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh -DMESHD_WERROR=ON
ctest --test-dir build --output-on-failure -j "$(nproc)"
