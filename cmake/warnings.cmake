# meshd::warnings — the one place where warning flags live; every target links it.
add_library(meshd_warnings INTERFACE)
add_library(meshd::warnings ALIAS meshd_warnings)
set(meshd_warning_flags -Wall -Wextra -Wshadow)
# GCC 12's -Wrestrict misfires inside libstdc++'s string concatenation at -O3 (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  list(APPEND meshd_warning_flags -Wno-restrict)
endif()
if(MESHD_WERROR)
  list(APPEND meshd_warning_flags -Werror)
endif()
target_compile_options(meshd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:${meshd_warning_flags}>)
string(REPLACE ";" "," meshd_nvcc_forward "${meshd_warning_flags}")
target_compile_options(meshd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CUDA>:-Xcompiler=${meshd_nvcc_forward}>)
