# Warning and sanitizer flags for the project's own targets (never for third-party code).
add_library(surfcomp_warnings INTERFACE)
target_compile_options(surfcomp_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter
  # GCC 12 reports maybe-uninitialized from inside OpenMesh property templates inlined into our code.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
if(SURFCOMP_WERROR)
  target_compile_options(surfcomp_warnings INTERFACE -Werror)
endif()
if(SURFCOMP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
if(SURFCOMP_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
if(SURFCOMP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SURFCOMP_FUZZ needs clang (libFuzzer): configure with the fuzz preset")
  endif()
  # Every project object gets coverage feedback and the sanitizers; fuzz/ links libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
