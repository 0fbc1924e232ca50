# Precompiled headers: the standard library, Eigen, nlohmann-json and Catch2 are parsed once per
# build instead of once per source file (parsing them is most of the time of a small file: 7.3 of
# the 7.8 s of a test file under the sanitizers, -ftime-report).
#
# BOXPILE_PCH: AUTO (the default) uses them unless a compiler launcher is set, because a compiler
# cache (CMAKE_CXX_COMPILER_LAUNCHER=ccache) cannot cache files compiled against a precompiled
# header, and a developer's rebuilds from the cache are faster than any precompiled header; and
# only with GCC, the compiler they were measured with (the fuzz build's clang compiles without).
set(BOXPILE_PCH AUTO CACHE STRING "Precompiled headers: AUTO (on unless a compiler launcher is set), ON or OFF")
set_property(CACHE BOXPILE_PCH PROPERTY STRINGS AUTO ON OFF)
if(BOXPILE_PCH STREQUAL "AUTO")
  if(CMAKE_CXX_COMPILER_LAUNCHER OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    set(boxpile_use_pch OFF)
  else()
    set(boxpile_use_pch ON)
  endif()
else()
  set(boxpile_use_pch ${BOXPILE_PCH})
endif()

# The headers of each level; a level includes the one before it.
set(boxpile_pch_core_headers
  <algorithm> <array> <cmath> <cstdint> <cstdio> <filesystem> <limits> <memory> <optional> <span>
  <stdexcept> <string> <string_view> <utility> <vector> <Eigen/Core> <Eigen/Geometry>)
set(boxpile_pch_json_headers ${boxpile_pch_core_headers} <nlohmann/json.hpp>)
set(boxpile_pch_cli_headers ${boxpile_pch_json_headers} <CLI/CLI.hpp>)
set(boxpile_pch_test_headers ${boxpile_pch_json_headers} <catch2/catch.hpp>)

# boxpile_precompile_headers(TARGET LEVEL): TARGET uses the precompiled header of LEVEL (core: the
# standard library and Eigen; json: also nlohmann-json; cli: also CLI11; test: also Catch2). The
# first target of a level builds it, the others reuse it, so the targets of one level must share
# their compile flags (build type, optimisation, sanitizers): GCC refuses a precompiled header
# built at another optimisation level. Private, so that nothing of it reaches the installed
# package's users.
function(boxpile_precompile_headers target level)
  if(NOT boxpile_use_pch)
    return()
  endif()
  get_property(owner GLOBAL PROPERTY boxpile_pch_owner_${level})
  if(owner)
    target_precompile_headers(${target} REUSE_FROM ${owner})
  else()
    target_precompile_headers(${target} PRIVATE ${boxpile_pch_${level}_headers})
    set_property(GLOBAL PROPERTY boxpile_pch_owner_${level} ${target})
  endif()
endfunction()
