# CTest script: install the dewall build tree into STAGING, then configure,
# build and run the consumer project against it (as a user would, with
# CMAKE_PREFIX_PATH pointing at the install).
include(${CMAKE_CURRENT_LIST_DIR}/../run_command.cmake)

file(REMOVE_RECURSE ${STAGING} ${CONSUMER_BUILD})
run(${CMAKE_COMMAND} --install ${DEWALL_BUILD_DIR} --prefix ${STAGING})
set(launcher)
if(CXX_LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD} -DCMAKE_PREFIX_PATH=${STAGING}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} ${launcher})
run(${CMAKE_COMMAND} --build ${CONSUMER_BUILD})
run(${CONSUMER_BUILD}/consumer)
