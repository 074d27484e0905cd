# ctest driver of a plain Verilog testbench under Icarus (label rtl):
#   cmake -DIVERILOG=… -DVVP=… -DTB=tb/icarus/<unit>_tb.sv -DTOP=<unit>_tb -DARGS="-y;rtl;pkg.sv;rtl.sv"
#         -DVECTORS=/abs/path/<unit>.hex -DWORK=<build dir> [-DSEED=n] -P run_icarus.cmake
# Compiles with `iverilog -g2012`, runs vvp with +vectors=<absolute path> (Icarus resolves
# $readmemh paths against the working directory) and +count=<manifest count>, and passes only
# when the bench prints PASSED and no MISMATCH.
foreach(v IVERILOG VVP TB TOP ARGS VECTORS WORK)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_icarus.cmake: -D${v}=… missing")
  endif()
endforeach()
if(NOT DEFINED SEED)
  set(SEED 1)
endif()
string(REGEX REPLACE "\\.hex$" ".json" manifest "${VECTORS}")
file(READ "${manifest}" mj)
string(JSON count GET "${mj}" count)
string(JSON word_bits GET "${mj}" word_bits)
file(MAKE_DIRECTORY "${WORK}")
set(exe "${WORK}/${TOP}.vvp")
execute_process(COMMAND "${IVERILOG}" -g2012 -o "${exe}" -s ${TOP} ${ARGS} "${TB}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc)
  message(FATAL_ERROR "iverilog failed (${rc}):\n${out}")
endif()
execute_process(COMMAND "${VVP}" -n "${exe}" +vectors=${VECTORS} +count=${count} +word_bits=${word_bits} +seed=${SEED}
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(rc OR NOT out MATCHES "\nPASSED" OR out MATCHES "MISMATCH|FAILED")
  message(FATAL_ERROR "Icarus testbench ${TOP} failed (exit ${rc})")
endif()
