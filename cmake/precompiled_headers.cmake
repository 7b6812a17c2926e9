# Precompiled headers: the standard library, Eigen, yaml-cpp and nlohmann-json (plus GoogleTest for
# the tests, CLI11 for the command line) are parsed once per build instead of once per source
# file. Each set is compiled in a small target of its own, retrace_pch_<kind>, and reused by every
# target that calls retrace_use_pch(<target> <kind>). RETRACE_PCH=OFF builds without them.

set(retrace_pch_lib_headers
  <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <limits> <map> <memory>
  <optional> <span> <string> <string_view> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry> <nlohmann/json.hpp> <yaml-cpp/yaml.h>)

# Optimization by need. A Release build compiles the per-tick code (core, sim, nav, the episode
# engine) and the micro benchmarks at -O3, and everything else (files, figures, commands, the
# Python module, the tests) at -O1 (retrace_cold): it runs once per run or once per command, and
# -O1 compiles it in about 40 % less time. The results are the same bits: with no fast-math and
# no contraction (-ffp-contract=off above), no optimization level changes a floating-point
# result, and the pinned hashes of the system tests check it. (GCC's precompiled headers carry
# their optimization level, so cold code has precompiled headers of its own.)
function(retrace_cold target)
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

# retrace_add_pch(<kind> [COLD] HEADERS <extra headers...> LIBS <targets whose definitions they
# need>): COLD for the precompiled headers of cold code (retrace_cold).
function(retrace_add_pch kind)
  cmake_parse_arguments(ARG "COLD" "" "HEADERS;LIBS" ${ARGN})
  if(NOT RETRACE_PCH)
    return()
  endif()
  file(WRITE ${CMAKE_BINARY_DIR}/retrace_pch_${kind}.cpp "// precompiled headers only\n")
  add_library(retrace_pch_${kind} OBJECT ${CMAKE_BINARY_DIR}/retrace_pch_${kind}.cpp)
  target_link_libraries(retrace_pch_${kind}
    PRIVATE Eigen3::Eigen yaml-cpp nlohmann_json::nlohmann_json ${ARG_LIBS})
  target_precompile_headers(retrace_pch_${kind} PRIVATE ${retrace_pch_lib_headers} ${ARG_HEADERS})
  if(ARG_COLD)
    retrace_cold(retrace_pch_${kind})
  endif()
endfunction()

function(retrace_use_pch target kind)
  if(RETRACE_PCH)
    target_precompile_headers(${target} REUSE_FROM retrace_pch_${kind})
  endif()
endfunction()

retrace_add_pch(lib)
retrace_add_pch(lib_cold COLD)
retrace_add_pch(cli COLD HEADERS <CLI/CLI.hpp> LIBS CLI11::CLI11)
