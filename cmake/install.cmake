# `cmake --install <build> [--prefix <dir>]`: the `retrace` program, the libraries with their
# headers (under include/retrace, included as in the tree: "bench/stack/navigation_stack.hpp"),
# and the CMake package `retrace`: a program outside the tree does find_package(retrace) and links
# retrace::cli to register a stack of its own and run every command on it
# (examples/external_stack, docs/DESIGN.md §6). Included after every target is defined.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(retrace_exported
  core io logs sim nav viz stack engine metrics output suite sweep compare replay run calibration
  worldgen crowd cli build_info)
set(retrace_export_targets "")
foreach(name IN LISTS retrace_exported)
  set_target_properties(retrace_${name} PROPERTIES EXPORT_NAME ${name})
  list(APPEND retrace_export_targets retrace_${name})
endforeach()
set(retrace_include_dir ${CMAKE_INSTALL_INCLUDEDIR}/retrace)
set(retrace_package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/retrace)

install(TARGETS retrace RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS retrace_video_codec LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/retrace)
install(TARGETS ${retrace_export_targets} EXPORT retraceTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${retrace_include_dir})
foreach(dir core io logs sim nav viz bench)
  install(DIRECTORY ${dir} DESTINATION ${retrace_include_dir}
          FILES_MATCHING PATTERN "*.hpp"
          PATTERN "micro" EXCLUDE PATTERN "suites" EXCLUDE PATTERN "sweeps" EXCLUDE)
endforeach()
install(EXPORT retraceTargets NAMESPACE retrace:: DESTINATION ${retrace_package_dir})
configure_package_config_file(cmake/retraceConfig.cmake.in
  ${PROJECT_BINARY_DIR}/retraceConfig.cmake INSTALL_DESTINATION ${retrace_package_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/retraceConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/retraceConfig.cmake
              ${PROJECT_BINARY_DIR}/retraceConfigVersion.cmake
        DESTINATION ${retrace_package_dir})
