# run(COMMAND...): runs a command from a CTest script (cmake -P), failing the
# script with the command line when it exits non-zero. Shared by the package
# tests (consumer/, fp_flags/).
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
