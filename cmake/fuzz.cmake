# MESHD_FUZZ: the libFuzzer targets of tests/fuzz (scripts/fuzz.sh drives them). Every target of
# the build is compiled with coverage instrumentation for libFuzzer (fuzzer-no-link) and with
# AddressSanitizer and UBSan, so that a fault anywhere on the request path is found where it
# happens; the fuzzers themselves link libFuzzer's main (tests/fuzz/CMakeLists.txt). Needs clang
# and a build without CUDA (nvcc cannot take these flags):
#   cmake -S . -B build-fuzz -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
#     -DMESHD_CUDA=OFF -DMESHD_FUZZ=ON
option(MESHD_FUZZ "Build the libFuzzer targets with ASan and UBSan (clang, MESHD_CUDA=OFF)" OFF)
if(MESHD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "MESHD_FUZZ=ON needs clang: configure with -DCMAKE_C_COMPILER=clang "
                        "-DCMAKE_CXX_COMPILER=clang++ (got ${CMAKE_CXX_COMPILER_ID})")
  endif()
  if(MESHD_HAVE_CUDA OR NOT MESHD_CUDA STREQUAL "OFF")
    message(FATAL_ERROR "MESHD_FUZZ=ON needs -DMESHD_CUDA=OFF")
  endif()
  # Undefined behaviour aborts at once (no recovery), so that libFuzzer records it as a crash.
  # No comparison tracing: in the distance evaluators' loops it more than doubled the time per
  # input, and the parsers whose constants it would help find (protobuf's) are not instrumented.
  string(JOIN " " MESHD_FUZZ_SANITIZERS -fsanitize=fuzzer-no-link,address,undefined
    -fno-sanitize-recover=all -fno-sanitize-coverage=trace-cmp -fno-omit-frame-pointer)
  # -O1 and line tables (after the build type's flags, so they win), as for the sanitizer
  # builds: a finding needs file and line, and full debug info at -O2 doubled the build's time.
  add_compile_options(-O1 -gline-tables-only)
  string(APPEND CMAKE_C_FLAGS " ${MESHD_FUZZ_SANITIZERS}")
  string(APPEND CMAKE_CXX_FLAGS " ${MESHD_FUZZ_SANITIZERS}")
  message(STATUS "meshd: fuzzing build (${MESHD_FUZZ_SANITIZERS})")
endif()
