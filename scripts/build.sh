#!/usr/bin/env bash
# Configures and builds meshd into build/ (Release). Extra arguments go to cmake's configure step,
# e.g. scripts/build.sh -DMESHD_WERROR=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j "$(nproc)"
