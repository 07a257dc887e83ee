# HAPTICCTRL_SANITIZER applies to the whole build so that every object is instrumented the same way.
if(HAPTICCTRL_SANITIZER STREQUAL "")
  return()
endif()
if(NOT HAPTICCTRL_SANITIZER MATCHES "^(address,undefined|address|undefined|thread)$")
  message(FATAL_ERROR "HAPTICCTRL_SANITIZER must be 'address,undefined' or 'thread', got '${HAPTICCTRL_SANITIZER}'")
endif()
add_compile_options(-fsanitize=${HAPTICCTRL_SANITIZER} -fno-omit-frame-pointer -fno-sanitize-recover=all)
add_link_options(-fsanitize=${HAPTICCTRL_SANITIZER})
add_compile_definitions(HAPTICCTRL_SANITIZED=1)
if(HAPTICCTRL_SANITIZER STREQUAL "thread")
  add_compile_definitions(HAPTICCTRL_TSAN=1)
endif()
if(CMAKE_C_COMPILER_ID STREQUAL "Clang")
  # A C program linked against the C++ client library (the VirtuoseAPI example and the
  # declarations' check) needs the C++ part of clang's UBSan runtime, which only its C++ driver
  # links.
  set(CMAKE_C_LINK_EXECUTABLE
    "${CMAKE_CXX_COMPILER} <FLAGS> <CMAKE_C_LINK_FLAGS> <LINK_FLAGS> <OBJECTS> -o <TARGET> <LINK_LIBRARIES>")
endif()
