# meshd::warnings — the one place where warning flags live; every target links it.
add_library(meshd_warnings INTERFACE)
add_library(meshd::warnings ALIAS meshd_warnings)
set(meshd_warning_flags -Wall -Wextra -Wshadow)
if(MESHD_WERROR)
  list(APPEND meshd_warning_flags -Werror)
endif()
target_compile_options(meshd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:${meshd_warning_flags}>)
string(REPLACE ";" "," meshd_nvcc_forward "${meshd_warning_flags}")
target_compile_options(meshd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CUDA>:-Xcompiler=${meshd_nvcc_forward}>)
