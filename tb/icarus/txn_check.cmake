# Shared by the Icarus transaction drivers (run_line_txn.cmake, run_stage_txn.cmake): compile a
# bench with iverilog, run it with vvp, print its log and judge it.
#   fxr_icarus_txn(TOP UNIT VVP_OUT COMPILE_ARGS PLUSARGS)
# passes when the log has PASSED and no MISMATCH; with CORRUPT defined (a row of the expected file
# flipped by the bench) when it has FAILED and exactly one MISMATCH, "MISMATCH <UNIT> row=<CORRUPT> ".
function(fxr_icarus_txn top unit vvp_out compile_args plusargs)
  execute_process(COMMAND ${IVERILOG} -g2012 -s ${top} -o "${vvp_out}" ${compile_args}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "iverilog failed:\n${out}${err}")
  endif()
  if(DEFINED CORRUPT)
    list(APPEND plusargs +corrupt=${CORRUPT})
  endif()
  execute_process(COMMAND ${VVP} -n "${vvp_out}" ${plusargs} RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  message("${log}${err}")
  string(REGEX MATCHALL "MISMATCH[^\n]*" mism "${log}")
  list(LENGTH mism nmism)
  if(DEFINED CORRUPT)
    if(NOT log MATCHES "\nFAILED" OR NOT nmism EQUAL 1 OR NOT log MATCHES "MISMATCH ${unit} row=${CORRUPT} ")
      message(FATAL_ERROR "the corrupted row ${CORRUPT} was not reported as exactly one mismatch")
    endif()
  elseif(NOT log MATCHES "\nPASSED" OR nmism GREATER 0)
    message(FATAL_ERROR "${top} (${unit}) failed")
  endif()
endfunction()
