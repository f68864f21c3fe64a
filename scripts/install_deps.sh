#!/usr/bin/env bash
# Installs the Debian packages meshd builds, tests and runs with, when any is missing.
# The CUDA toolkit is not installed here: the GPU engine is built only where nvcc exists.
# --fuzz adds what scripts/fuzz.sh needs (clang and its libFuzzer and sanitizer runtimes), which
# the normal build does not.
set -euo pipefail
fuzz_packages=(clang-14 libclang-rt-14-dev)
packages=(
  build-essential cmake ninja-build pkg-config
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libcgal-dev libtbb-dev libspdlog-dev libfmt-dev libgtest-dev libgmock-dev prometheus-cpp-dev libssl-dev
  python3 python3-meshio python3-grpcio python3-protobuf gmsh openssl valgrind
  python3-numpy python3-venv python3-setuptools python3-wheel
  libgdal-dev gdal-bin python3-gdal
  gmt gmt-gshhg-high
)
[ "${1:-}" = "--fuzz" ] && packages+=("${fuzz_packages[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install_deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
