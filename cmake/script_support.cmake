# Shared by the ctest scripts run with `cmake -P` (tests/downstream/run_downstream.cmake, python/tests/run_*.cmake).

# hilite_require(SCRIPT VAR...): each -DVAR=... given, else a fatal error naming the script and the variable.
function(hilite_require script)
  foreach(v IN LISTS ARGN)
    if(NOT DEFINED ${v})
      message(FATAL_ERROR "${script}: -D${v}=... is required")
    endif()
  endforeach()
endfunction()

# run(COMMAND...): runs it (in WORK_DIR when set), a fatal error with the command and its output when it fails;
# its stdout in run_out.
function(run)
  set(dir "${CMAKE_CURRENT_BINARY_DIR}")
  if(DEFINED WORK_DIR)
    set(dir "${WORK_DIR}")
  endif()
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${dir} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " cmd)
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()
