# hapticctrl_add_xdr_library(<target> <file.x>)
# Generates C from an RFC 4506 .x file with rpcgen (header + XDR routines) and builds it as a
# static, position-independent C library linked with libtirpc. The generated header is found as
# "<name>.h" through the target's include directories.
#
# rpcgen quirks handled here (docs/protocol.md): it refuses to overwrite its outputs, so they
# are removed first; it copies the input path into its #include, so it runs on a copy of the
# .x file in the output directory; its output is C and is compiled without our warnings.
find_package(PkgConfig REQUIRED)
pkg_check_modules(TIRPC REQUIRED IMPORTED_TARGET libtirpc)
find_program(RPCGEN_EXECUTABLE rpcgen REQUIRED)

function(hapticctrl_add_xdr_library target x_file)
  get_filename_component(x_abs ${x_file} ABSOLUTE)
  get_filename_component(name ${x_file} NAME_WE)
  # Outside the source-like paths of .clang-tidy's HeaderFilterRegex: generated code is not linted.
  set(out_dir ${CMAKE_BINARY_DIR}/generated/xdr)
  set(out_h ${out_dir}/${name}.h)
  set(out_c ${out_dir}/${name}_xdr.c)
  add_custom_command(
    OUTPUT ${out_h} ${out_c}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
    COMMAND ${CMAKE_COMMAND} -E remove -f ${out_h} ${out_c}
    COMMAND ${CMAKE_COMMAND} -E copy ${x_abs} ${out_dir}/${name}.x
    COMMAND ${RPCGEN_EXECUTABLE} -h -o ${name}.h ${name}.x
    COMMAND ${RPCGEN_EXECUTABLE} -c -o ${name}_xdr.c ${name}.x
    WORKING_DIRECTORY ${out_dir}
    DEPENDS ${x_abs}
    COMMENT "rpcgen ${name}.x"
    VERBATIM)
  add_library(${target} STATIC ${out_c} ${out_h})
  set_source_files_properties(${out_c} PROPERTIES COMPILE_OPTIONS "-w")
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${out_dir}>)
  target_link_libraries(${target} PUBLIC PkgConfig::TIRPC)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON LINKER_LANGUAGE C)
endfunction()
