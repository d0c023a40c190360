# CTest script for one row of the floating-point flags table (README,
# "What is guaranteed"): install the build tree into a staging prefix, build
# examples/fp_flags with COMPILER and FLAGS, and check that
#  * the program on the default kernel builds, and gives exactly CGAL's cells on
#    every degenerate set (CGAL's computed by the dewall CLI, built with safe
#    flags), each certified canonical by `dewall certify --canonical`;
#  * the program on a user kernel (header-only path) either refuses to compile
#    with a message naming the flag (REFUSES=ON) or builds and passes the same
#    checks (REFUSES=OFF).
# Variables: DEWALL_BUILD_DIR, SOURCE, WORK, COMPILER, FLAGS, LAUNCHER, CLI, REFUSES.
include(${CMAKE_CURRENT_LIST_DIR}/../run_command.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/data)
run(${CMAKE_COMMAND} --install ${DEWALL_BUILD_DIR} --prefix ${WORK}/prefix)
set(launcher)
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
message(STATUS "compiler ${COMPILER}, flags '${FLAGS}'")
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -DCMAKE_PREFIX_PATH=${WORK}/prefix
    -DCMAKE_CXX_COMPILER=${COMPILER} "-DCMAKE_CXX_FLAGS=${FLAGS}" -DCMAKE_BUILD_TYPE= ${launcher})
run(${CMAKE_COMMAND} --build ${WORK}/build --target probe)

# The user-kernel program: refused or built.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build --target probe_user_kernel
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(REFUSES)
  if(rc EQUAL 0)
    message(FATAL_ERROR "the user-kernel program compiled with '${FLAGS}'; it must refuse")
  endif()
  if(NOT "${out}${err}" MATCHES "dewall: [^\n]*compiled with [^\n]*(-ffast-math|-Ofast|-funsafe-math|-ffinite-math)")
    message(FATAL_ERROR "the user-kernel program failed to compile without naming the flag:\n${out}${err}")
  endif()
  string(REGEX MATCH "dewall: [^\n]*" refusal "${out}${err}")
  message(STATUS "user kernel refused at compile time: ${refusal}")
  set(programs probe)
else()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the user-kernel program did not compile with '${FLAGS}':\n${out}${err}")
  endif()
  set(programs probe probe_user_kernel)
endif()

execute_process(COMMAND ${WORK}/build/probe write ${WORK}/data OUTPUT_VARIABLE names RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "probe write failed")
endif()
string(REGEX MATCHALL "[a-z_0-9]+" names "${names}")
foreach(name IN LISTS names)
  run(${CLI} triangulate --engine cgal ${WORK}/data/${name}.xyz -o ${WORK}/data/${name}.cgal.txt)
endforeach()
foreach(program IN LISTS programs)
  execute_process(COMMAND ${WORK}/build/${program} check ${WORK}/data RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  message(STATUS "${program}:\n${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${program} check failed")
  endif()
  # Linking with these flags turns on flush-to-zero (crtfastmath.o): make sure
  # the row tested the library under it.
  if(FLAGS MATCHES "fast-math|Ofast|unsafe-math" AND CMAKE_HOST_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64"
     AND NOT out MATCHES "FTZ/DAZ on")
    message(FATAL_ERROR "${program} did not start with FTZ/DAZ on; the row does not test what it says")
  endif()
  if(program STREQUAL "probe")
    set(tag dewall)
  else()
    set(tag user)
  endif()
  foreach(name IN LISTS names)
    run(${CLI} certify --canonical ${WORK}/data/${name}.xyz ${WORK}/data/${name}.${tag}.simplices)
  endforeach()
endforeach()
