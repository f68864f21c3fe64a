# MESHD_SANITIZE: build everything with these sanitizers, e.g. "address,undefined" or "thread"
# (host code only: configure with -DMESHD_CUDA=OFF). scripts/sanitize.sh drives it.
set(MESHD_SANITIZE "" CACHE STRING "Sanitizers for every target: address,undefined or thread")
if(MESHD_SANITIZE)
  if(MESHD_HAVE_CUDA)
    message(FATAL_ERROR "MESHD_SANITIZE needs -DMESHD_CUDA=OFF (compute-sanitizer covers kernels)")
  endif()
  # -O1 and line tables only (after the build type's flags, so they win): a report needs file
  # and line, not locals, and full debug info at -O2 took twice as long to build CGAL's code.
  set(meshd_sanitize_flags -fsanitize=${MESHD_SANITIZE} -fno-omit-frame-pointer -O1 -g1)
  if(MESHD_SANITIZE MATCHES "undefined")
    # A UBSan report fails the test instead of printing and going on.
    list(APPEND meshd_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  # GCC's flow analysis sees the sanitizers' instrumentation and warns about values that are
  # initialised (std::regex's automaton in libstdc++ 12): a false positive under -Werror.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    list(APPEND meshd_sanitize_flags -Wno-maybe-uninitialized)
  endif()
  add_compile_options(${meshd_sanitize_flags})
  add_link_options(-fsanitize=${MESHD_SANITIZE})
endif()
