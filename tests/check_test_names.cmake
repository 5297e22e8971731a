# SPDX-License-Identifier: MIT
# ctest runs each doctest case by name (doctest_discover_tests), and a ';' in
# a name splits it as a CMake list: the test then selects no case and passes
# without running anything. Fails naming every TEST_CASE whose name has one.
file(GLOB_RECURSE sources "${TESTS}/*.cpp")
set(bad "")
foreach(source ${sources})
  file(STRINGS "${source}" lines REGEX "TEST_CASE\\(\"[^\"]*\;")
  foreach(line ${lines})
    string(APPEND bad "\n  ${source}: ${line}")
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "test case names with ';' run nothing under ctest; use ',':${bad}")
endif()
