# One interface target carries the house warning flags; every rodlab target links it.
add_library(rodlab_warnings INTERFACE)
target_compile_options(rodlab_warnings INTERFACE -Wall -Wextra -Wpedantic)
if(RODLAB_WERROR)
  target_compile_options(rodlab_warnings INTERFACE -Werror)
endif()
