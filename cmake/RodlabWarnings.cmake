# One interface target carries the house warning flags; every rodlab target links it.
add_library(rodlab_warnings INTERFACE)
target_compile_options(rodlab_warnings INTERFACE -Wall -Wextra -Wpedantic)
if(RODLAB_WERROR)
  target_compile_options(rodlab_warnings INTERFACE -Werror)
endif()

# -DRODLAB_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on every rodlab target (and
# the link), undefined behaviour fatal. Run the tests with ASAN_OPTIONS and LSAN_OPTIONS as
# docs/development.md says (OpenMPI's own start-up leaks need the suppression file there).
if(RODLAB_SANITIZE)
  target_compile_options(rodlab_warnings INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g)
  target_link_options(rodlab_warnings INTERFACE -fsanitize=address,undefined)
  # GCC 12 with -fsanitize=address at -O1 reports std::regex's std::function members as "may be
  # used uninitialized" (inside libstdc++, tests/cli/test_cli.cpp): false positives that would
  # stop CI's -Werror build. The Release build keeps the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(rodlab_warnings INTERFACE -Wno-maybe-uninitialized)
  endif()
endif()

# -DRODLAB_FUZZ=ON (clang): every rodlab target instrumented for libFuzzer's coverage and built
# with AddressSanitizer + UndefinedBehaviorSanitizer (undefined behaviour fatal); the fuzz
# targets themselves link -fsanitize=fuzzer (fuzz/CMakeLists.txt).
if(RODLAB_FUZZ)
  target_compile_options(rodlab_warnings INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
    -fno-omit-frame-pointer -g)
  target_link_options(rodlab_warnings INTERFACE -fsanitize=address,undefined)
endif()
