# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# cmake -DCXX=... -DINCLUDE=... -DSRC=... -DEXPECT=fail|pass [-DMESSAGE=regex] -P check.cmake
# Compiles SRC (syntax and templates, no object) and checks that it fails with an error matching
# MESSAGE (EXPECT=fail) or succeeds (EXPECT=pass).
execute_process(
  COMMAND ${CXX} -std=c++17 -fsyntax-only -I${INCLUDE} ${SRC}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(EXPECT STREQUAL "pass")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${SRC} should compile but does not:\n${err}")
  endif()
  message(STATUS "compiles, as it should: ${SRC}")
else()
  if(rc EQUAL 0)
    message(FATAL_ERROR "${SRC} compiles but must not (the silent trap is back)")
  endif()
  if(DEFINED MESSAGE AND NOT err MATCHES "${MESSAGE}")
    message(FATAL_ERROR "${SRC} fails to compile, but not with the expected message "
                        "(${MESSAGE}):\n${err}")
  endif()
  message(STATUS "fails to compile, as it should: ${SRC}")
endif()
