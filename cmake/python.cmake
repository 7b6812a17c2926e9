# The Python module `retrace` (python/, docs/PYTHON.md): pybind11 bindings of the library calls.
# RETRACE_PYTHON: AUTO (the default) builds it when pybind11, Python 3 (interpreter and headers)
# and NumPy are found, and not under the sanitizers or libFuzzer (an extension module would need
# their runtimes preloaded into the interpreter); ON requires it; OFF skips it. Sets
# RETRACE_BUILD_PYTHON. Included before the libraries: a shared module links them, so they are
# compiled as position-independent code (-fPIC) when it is built.

set(RETRACE_PYTHON AUTO CACHE STRING
    "Build the Python module retrace (python/): AUTO (when pybind11, Python 3 and NumPy are found), ON, OFF")
set_property(CACHE RETRACE_PYTHON PROPERTY STRINGS AUTO ON OFF)
# Debian's interpreter, which has NumPy and pytest (another python3 earlier on PATH may not).
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the module is built for")
endif()

set(RETRACE_BUILD_PYTHON OFF)
set(retrace_python_why "")
if(RETRACE_PYTHON STREQUAL "OFF")
  set(retrace_python_why "RETRACE_PYTHON=OFF")
elseif(RETRACE_PYTHON STREQUAL "AUTO" AND (RETRACE_SANITIZE OR RETRACE_FUZZ))
  set(retrace_python_why "not in a sanitizer or fuzzing build")
else()
  find_package(Python3 COMPONENTS Interpreter Development.Module NumPy)
  if(Python3_FOUND)
    find_package(pybind11 CONFIG)
  endif()
  if(Python3_FOUND AND pybind11_FOUND)
    set(RETRACE_BUILD_PYTHON ON)
  else()
    set(retrace_python_why
        "pybind11, Python 3's headers or NumPy not found: apt-get install pybind11-dev python3-dev python3-numpy")
  endif()
endif()

if(RETRACE_BUILD_PYTHON)
  message(STATUS "Python module retrace: on (${Python3_EXECUTABLE}, pybind11 ${pybind11_VERSION}); "
                 "import with PYTHONPATH=${PROJECT_BINARY_DIR}/python")
  # Everything as -fPIC (not CMAKE_POSITION_INDEPENDENT_CODE, which gives executables -fPIE: the
  # precompiled headers they share with the libraries must be built with the same flags).
  # -fno-semantic-interposition keeps -fPIE's code: under -fPIC alone GCC may not inline a
  # function another library could interpose, and these libraries are linked statically.
  add_compile_options(-fPIC)
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag(-fno-semantic-interposition RETRACE_HAS_NO_SEMANTIC_INTERPOSITION)
  if(RETRACE_HAS_NO_SEMANTIC_INTERPOSITION)
    add_compile_options(-fno-semantic-interposition)
  endif()
elseif(RETRACE_PYTHON STREQUAL "ON")
  message(FATAL_ERROR "RETRACE_PYTHON=ON, but ${retrace_python_why}")
else()
  message(STATUS "Python module retrace: off (${retrace_python_why})")
endif()
