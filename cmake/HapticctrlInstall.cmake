# What `cmake --install` puts on a machine (docs/deployment.md): the programs, the shipped arm
# model, the web page, the documentation, and the systemd units and sysusers file that run the
# core and the bridges as the hapticctrl system user. The units name the installed paths.
set(HAPTICCTRL_BINDIR ${CMAKE_INSTALL_FULL_BINDIR})
set(HAPTICCTRL_DATADIR ${CMAKE_INSTALL_FULL_DATADIR}/hapticctrl)
set(HAPTICCTRL_DOCDIR ${CMAKE_INSTALL_FULL_DOCDIR})

# The demo links the client library, installed beside the programs: found relative to itself, so
# the installed tree works wherever it lands (a staging root, a prefix without ldconfig).
set_target_properties(hapticctrl-demo PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
install(TARGETS hapticctrl-core hapticctrl-udp hapticctrl-lcm hapticctrl-log2csv hapticctrl-web
                hapticctrl-hmi hapticctrl-demo hapticctrl-dds hapticctrl-dds-listen
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PROJECT_SOURCE_DIR}/arm_model/models/virtuose6d_class.arm
        DESTINATION ${CMAKE_INSTALL_DATADIR}/hapticctrl/models)
if(TARGET hapticctrl_web_page)
  install(DIRECTORY ${HAPTICCTRL_WEB_WWW_DIR}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/hapticctrl/www)
endif()
file(GLOB doc_files ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES ${doc_files} DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(unit_files "")
foreach(unit core udp lcm web dds)
  set(unit_file ${PROJECT_BINARY_DIR}/systemd/hapticctrl-${unit}@.service)
  configure_file(${PROJECT_SOURCE_DIR}/scripts/systemd/hapticctrl-${unit}@.service.in ${unit_file}
                 @ONLY)
  list(APPEND unit_files ${unit_file})
endforeach()
install(FILES ${unit_files} DESTINATION lib/systemd/system)
install(FILES ${PROJECT_SOURCE_DIR}/scripts/systemd/hapticctrl.sysusers
        DESTINATION lib/sysusers.d RENAME hapticctrl.conf)
