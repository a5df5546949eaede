# Warning and sanitizer flags for the project's own targets (never for third-party code).
add_library(surfcomp_warnings INTERFACE)
target_compile_options(surfcomp_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter
  # GCC 12 reports maybe-uninitialized from inside OpenMesh property templates inlined into our code.
  -Wno-maybe-uninitialized)
if(SURFCOMP_WERROR)
  target_compile_options(surfcomp_warnings INTERFACE -Werror)
endif()
if(SURFCOMP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
