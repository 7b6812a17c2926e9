# Precompiled headers: the standard library, Eigen, yaml-cpp and nlohmann-json (plus GoogleTest for
# the tests, CLI11 for the command line) are parsed once per build instead of once per source
# file. Each set is compiled in a small target of its own, retrace_pch_<kind>, and reused by every
# target that calls retrace_use_pch(<target> <kind>). RETRACE_PCH=OFF builds without them.

set(retrace_pch_lib_headers
  <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <limits> <map> <memory>
  <optional> <span> <string> <string_view> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry> <nlohmann/json.hpp> <yaml-cpp/yaml.h>)

# retrace_add_pch(<kind> HEADERS <extra headers...> LIBS <targets whose definitions they need>)
function(retrace_add_pch kind)
  cmake_parse_arguments(ARG "" "" "HEADERS;LIBS" ${ARGN})
  if(NOT RETRACE_PCH)
    return()
  endif()
  file(WRITE ${CMAKE_BINARY_DIR}/retrace_pch_${kind}.cpp "// precompiled headers only\n")
  add_library(retrace_pch_${kind} OBJECT ${CMAKE_BINARY_DIR}/retrace_pch_${kind}.cpp)
  target_link_libraries(retrace_pch_${kind}
    PRIVATE Eigen3::Eigen yaml-cpp nlohmann_json::nlohmann_json ${ARG_LIBS})
  target_precompile_headers(retrace_pch_${kind} PRIVATE ${retrace_pch_lib_headers} ${ARG_HEADERS})
endfunction()

function(retrace_use_pch target kind)
  if(RETRACE_PCH)
    target_precompile_headers(${target} REUSE_FROM retrace_pch_${kind})
  endif()
endfunction()

retrace_add_pch(lib)
retrace_add_pch(cli HEADERS <CLI/CLI.hpp> LIBS CLI11::CLI11)
