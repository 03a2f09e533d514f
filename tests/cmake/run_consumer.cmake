# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Configures, builds and runs tests/cmake/consumer twice: via add_subdirectory and via find_package
# from an install prefix. Fails on the first error.
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(consumer ${SOURCE_DIR}/tests/cmake/consumer)

# 1. install ebgeom into a prefix, then find_package it
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/ebgeom -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DEBGEOM_BUILD_TESTS=OFF -DEBGEOM_BUILD_CLI=OFF
    -DEBGEOM_BUILD_EXAMPLES=OFF -DCMAKE_INSTALL_PREFIX=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/ebgeom)
run(${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/by_package -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DUSE_SUBDIRECTORY=OFF)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/by_package)
run(${WORK_DIR}/by_package/consumer)

# 1b. a request for a newer version than the installed one must fail (0.x: minor versions differ)
foreach(too_new 0.2 1.0)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/too_new_${too_new}
                  -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                  -DUSE_SUBDIRECTORY=OFF -DREQUEST_VERSION=${too_new}
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "not compatible|version")
    message(FATAL_ERROR "find_package(ebgeom ${too_new}) should fail against 0.1.x (rc ${rc})\n${err}")
  endif()
endforeach()

# 2. add_subdirectory
run(${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/by_subdir -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DUSE_SUBDIRECTORY=ON -DEBGEOM_SOURCE_DIR=${SOURCE_DIR})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/by_subdir)
run(${WORK_DIR}/by_subdir/consumer)
