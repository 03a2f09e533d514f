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

# 2. add_subdirectory
run(${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/by_subdir -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DUSE_SUBDIRECTORY=ON -DEBGEOM_SOURCE_DIR=${SOURCE_DIR})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/by_subdir)
run(${WORK_DIR}/by_subdir/consumer)
