# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Builds test sources with a second compiler (Clang, default flags: no -march) and runs them. The
# run-time dispatched kernels must give the same bits as the brute force under every compiler:
# Clang contracts a*b + c into fused multiply-adds by default, inside AVX2 kernels but not in a
# build without FMA. SRCS (each source one test program), GTEST_LIBS, GTEST_INCS: lists separated
# by '|'.
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

string(REPLACE "|" ";" gtest_libs "${GTEST_LIBS}")
string(REPLACE "|" ";" gtest_incs "${GTEST_INCS}")
set(inc_flags)
foreach(dir ${gtest_incs} ${SOURCE_DIR}/include ${SOURCE_DIR}/tests/support)
  list(APPEND inc_flags -I${dir})
endforeach()
file(MAKE_DIRECTORY ${WORK_DIR})
string(REPLACE "|" ";" srcs "${SRCS}")
foreach(src ${srcs})
  get_filename_component(name ${src} NAME_WE)
  get_filename_component(dir ${SOURCE_DIR}/${src} DIRECTORY)
  run(${CXX} -std=c++17 -O2 -DEBGEOM_ENABLE_ASSERTS "-DEBGEOM_TEST_MESH_DIR=\"${MESH_DIR}\""
      "-DEBGEOM_TEST_DATA_DIR=\"${SOURCE_DIR}/tests/data\"" ${inc_flags} -I${dir}
      ${SOURCE_DIR}/${src} -o ${WORK_DIR}/${name} ${gtest_libs} -pthread)
  run(${WORK_DIR}/${name} --gtest_brief=1)
endforeach()
