# C types from an IDL file, generated at build time by Cyclone DDS's idlc (Debian:
# cyclonedds-tools), as a static library `target` whose users include "<idl name>.h".
find_package(CycloneDDS REQUIRED)
find_program(IDLC_EXECUTABLE idlc REQUIRED)

function(hapticctrl_idl_library target idl)
  get_filename_component(idl ${idl} ABSOLUTE)
  get_filename_component(name ${idl} NAME_WE)
  set(gen ${CMAKE_CURRENT_BINARY_DIR}/${target}_gen)
  add_custom_command(
    OUTPUT ${gen}/${name}.c ${gen}/${name}.h
    COMMAND ${CMAKE_COMMAND} -E make_directory ${gen}
    # Final extensibility: plain CDR, as ROS 2's rmw_cyclonedds writes its messages.
    COMMAND ${IDLC_EXECUTABLE} -x final -o ${gen} ${idl}
    DEPENDS ${idl}
    COMMENT "idlc: ${name}.idl"
    VERBATIM)
  # Generated code is not ours to warn about.
  set_source_files_properties(${gen}/${name}.c PROPERTIES COMPILE_OPTIONS "-w")
  add_library(${target} STATIC ${gen}/${name}.c)
  target_include_directories(${target} SYSTEM PUBLIC ${gen})
  target_link_libraries(${target} PUBLIC CycloneDDS::ddsc)
endfunction()
