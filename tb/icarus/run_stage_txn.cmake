# ctest driver of tb/icarus/stage_txn_tb.sv: one stage with record ports (fxr_clip,
# fxr_recip_stage for STAGE recip, fxr_viewport, fxr_setup, fxr_traverse, fxr_interp, fxr_depth,
# fxr_divide) on a transaction dump's S.in / S.out under
# Icarus 11 (docs/rtl.md, "Icarus on the record ports"):
#   cmake -DIVERILOG=… -DVVP=… -DTB=tb/icarus/stage_txn_tb.sv -DRTL=rtl -DPKGS="cfg_pkg.sv;rec_pkg.sv"
#         -DSTAGE=traverse -DDUMP=/abs/dump -DWORK=<build dir> [-DSEED=n] [-DCORRUPT=row]
#         [-DWRITEPORT=1] -P run_stage_txn.cmake
# 1. Icarus 11 aborts on a package-qualified type (`fxr_rec_pkg::span_t`, elab_type.cc:86) and does
#    not parse elaboration-time `$error` in a generate block, while Yosys 0.23 (which the RTL must
#    keep reading) has no `import` at file or module-header scope: the RTL is copied into WORK with
#    `fxr_rec_pkg::<name>_t` → `<name>_t` (one `import fxr_rec_pkg::*;` ahead of it) and `$error(`
#    → `initial $fatal(1, ` (every `$error` of rtl/ is an elaboration check); nothing else changes.
#    The stage's own file is given on the command line: found through `-y` (a library file),
#    a module with a struct port still hits the abort.
# 2. From the manifests (S.in.json, S.out.json; interp: setup.out.json for ctx_i) and scene.json's
#    draw_state it writes WORK/stage_txn_gen.svh: the word widths, row counts, header offsets,
#    the record of a line as one function per file (the record's fields, after the header,
#    concatenated first-most-significant: the struct port's layout), the first differing field
#    of an output record by name, and the draw state. So no layout is written by hand.
# 3. Compiles with `iverilog -g2012`, runs vvp; passes when the bench prints PASSED and no
#    MISMATCH; with -DCORRUPT=N (one bit of expected row N flipped by the bench) when it prints
#    FAILED and exactly one MISMATCH, at row N.
foreach(v IVERILOG VVP TB RTL PKGS STAGE DUMP WORK)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_stage_txn.cmake: -D${v}=… missing")
  endif()
endforeach()
if(NOT DEFINED SEED)
  set(SEED 1)
endif()
if(NOT DEFINED WRITEPORT)
  set(WRITEPORT 0)
endif()
cmake_policy(VERSION 3.20)
# Several dumps (DUMP a list): this script once per dump, in WORK/<n>.
list(LENGTH DUMP ndumps)
if(ndumps GREATER 1)
  set(i 0)
  foreach(d IN LISTS DUMP)
    set(extra "")
    if(DEFINED CORRUPT)
      set(extra -DCORRUPT=${CORRUPT})
    endif()
    execute_process(COMMAND ${CMAKE_COMMAND} -DIVERILOG=${IVERILOG} -DVVP=${VVP} -DTB=${TB} -DRTL=${RTL}
                            "-DPKGS=${PKGS}" -DSTAGE=${STAGE} -DDUMP=${d} -DWORK=${WORK}/${i} -DSEED=${SEED}
                            -DWRITEPORT=${WRITEPORT} ${extra} -P ${CMAKE_CURRENT_LIST_FILE}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    string(REGEX MATCHALL "[^\n]*(errors=|PASSED|FAILED|MISMATCH|Error|error)[^\n]*" lines "${out}${err}")
    string(REPLACE ";" "\n" lines "${lines}")
    message("${d}:\n${lines}")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${STAGE} on ${d} failed:\n${out}${err}")
    endif()
    math(EXPR i "${i} + 1")
  endforeach()
  return()
endif()
set(modules clip recip viewport setup traverse interp depth divide)
if(NOT STAGE IN_LIST modules)
  message(FATAL_ERROR "run_stage_txn.cmake: STAGE must be one of ${modules}")
endif()

# 1. The RTL as Icarus reads it.
file(REMOVE_RECURSE "${WORK}/rtl")
file(MAKE_DIRECTORY "${WORK}/rtl")
file(GLOB srcs "${RTL}/*.sv")
foreach(f ${srcs})
  file(READ "${f}" t)
  string(REGEX REPLACE "fxr_rec_pkg::([A-Za-z0-9_]+_t)([^A-Za-z0-9_])" "\\1\\2" t "${t}")
  string(REPLACE "$error(" "initial $fatal(1, " t "${t}")
  get_filename_component(n "${f}" NAME)
  file(WRITE "${WORK}/rtl/${n}" "${t}")
endforeach()
file(WRITE "${WORK}/rec_import.sv" "import fxr_rec_pkg::*;  // run_stage_txn.cmake: see step 1\n")

# 2. The generated part of the bench.
# manifest(FILE PREFIX HEADER): PREFIX_word, PREFIX_count, PREFIX_rec (the concatenation),
# PREFIX_recbits, and the offsets of header / named fields as PREFIX_off_<name>, PREFIX_pos_<name>
# (position inside the record), PREFIX_w_<name>; PREFIX_names / PREFIX_poss / PREFIX_widths lists.
function(manifest file prefix header)
  file(READ "${file}" j)
  string(JSON bits GET "${j}" word_bits)
  string(JSON count GET "${j}" count)
  string(JSON n LENGTH "${j}" fields)
  math(EXPR last "${n} - 1")
  set(parts "")
  set(names "")
  set(widths "")
  set(recbits 0)
  foreach(i RANGE ${last})
    string(JSON name GET "${j}" fields ${i} name)
    string(JSON off GET "${j}" fields ${i} offset)
    string(JSON w GET "${j}" fields ${i} width)
    set(${prefix}_off_${name} ${off} PARENT_SCOPE)
    set(${prefix}_w_${name} ${w} PARENT_SCOPE)
    if(i GREATER_EQUAL header)
      list(APPEND parts "w[${off} +: ${w}]")
      list(APPEND names ${name})
      list(APPEND widths ${w})
      math(EXPR recbits "${recbits} + ${w}")
    endif()
  endforeach()
  # positions inside the record: the last field at 0
  set(pos ${recbits})
  set(poss "")
  foreach(w ${widths})
    math(EXPR pos "${pos} - ${w}")
    list(APPEND poss ${pos})
  endforeach()
  list(LENGTH names nn)
  math(EXPR nl "${nn} - 1")
  foreach(k RANGE ${nl})
    list(GET names ${k} nm)
    list(GET poss ${k} p)
    set(${prefix}_pos_${nm} ${p} PARENT_SCOPE)
  endforeach()
  string(REPLACE ";" ", " rec "${parts}")
  set(${prefix}_word ${bits} PARENT_SCOPE)
  set(${prefix}_count ${count} PARENT_SCOPE)
  set(${prefix}_rec "{${rec}}" PARENT_SCOPE)
  set(${prefix}_recbits ${recbits} PARENT_SCOPE)
  set(${prefix}_names "${names}" PARENT_SCOPE)
  set(${prefix}_poss "${poss}" PARENT_SCOPE)
  set(${prefix}_widths "${widths}" PARENT_SCOPE)
endfunction()

set(in_header 2)
if(STAGE STREQUAL "interp")
  set(in_header 3)
endif()
manifest("${DUMP}/${STAGE}.in.json" in ${in_header})
manifest("${DUMP}/${STAGE}.out.json" out 3)
if(STAGE STREQUAL "interp")
  manifest("${DUMP}/setup.out.json" ctx 3)
  set(ctx_file "${DUMP}/setup.out.hex")
else()
  set(ctx_word 1)
  set(ctx_count 0)
  set(ctx_rec "w")
  set(ctx_recbits 1)
  set(ctx_file "${DUMP}/${STAGE}.in.hex")
  set(in_off_ctx 0)
endif()
string(TOUPPER "${STAGE}" STAGE_UC)

file(READ "${DUMP}/scene.json" sj)
set(ds "")
foreach(k viewport_x viewport_y viewport_w viewport_h scissor_x scissor_y scissor_w scissor_h cull front_ccw interp
          depth_func depth_test depth_write)
  string(JSON v GET "${sj}" draw_state ${k})
  string(APPEND ds "  localparam int Ds_${k} = ${v};\n")
endforeach()

set(diff "")
list(LENGTH out_names nn)
math(EXPR nl "${nn} - 1")
foreach(k RANGE ${nl})
  list(GET out_names ${k} nm)
  list(GET out_poss ${k} p)
  list(GET out_widths ${k} w)
  string(APPEND diff "    if (g[${p} +: ${w}] !== e[${p} +: ${w}]) return \"${nm}\";\n")
endforeach()

set(depth_pos "")
if(STAGE STREQUAL "depth")
  string(APPEND depth_pos "  localparam int OutPosX = ${out_pos_x}, OutPosY = ${out_pos_y}, OutPosDepth = ${out_pos_depth};\n")
  string(APPEND depth_pos "  localparam int OutWX = ${out_w_x}, OutWDepth = ${out_w_depth};\n")
endif()

file(WRITE "${WORK}/stage_txn_gen.svh"
"// GENERATED by tb/icarus/run_stage_txn.cmake from ${DUMP}/${STAGE}.{in,out}.json and scene.json
`define FXR_STAGE_${STAGE_UC}
`define FXR_STAGE_NAME \"${STAGE}\"
  localparam int InWordBits = ${in_word}, OutWordBits = ${out_word}, CtxWordBits = ${ctx_word};
  localparam int NIn = ${in_count}, NOut = ${out_count}, NCtx = ${ctx_count};
  localparam int InRecBits = ${in_recbits}, OutRecBits = ${out_recbits}, CtxRecBits = ${ctx_recbits};
  localparam int InTxnOff = ${in_off_txn}, InNOutOff = ${in_off_n_out}, InCtxOff = ${in_off_ctx};
  localparam int OutTxnOff = ${out_off_txn}, OutSeqOff = ${out_off_seq}, OutLastOff = ${out_off_last};
  localparam bit WritePort = 1'b${WRITEPORT};
${ds}${depth_pos}
  function automatic logic [InRecBits-1:0] in_rec(input logic [InWordBits-1:0] w);
    return ${in_rec};
  endfunction
  function automatic logic [OutRecBits-1:0] out_rec(input logic [OutWordBits-1:0] w);
    return ${out_rec};
  endfunction
  function automatic logic [CtxRecBits-1:0] ctx_rec(input logic [CtxWordBits-1:0] w);
    return ${ctx_rec};
  endfunction
  // The first field (in record order) where got and expected differ.
  function automatic string out_diff(input logic [OutRecBits-1:0] g, input logic [OutRecBits-1:0] e);
${diff}    return \"\";
  endfunction
")

# 3. Compile and run.
include(${CMAKE_CURRENT_LIST_DIR}/txn_check.cmake)
set(module fxr_${STAGE})
if(STAGE STREQUAL "recip")
  set(module fxr_recip_stage)  # stage 3's record-port module (fxr_recip is its lane)
endif()
fxr_icarus_txn(stage_txn_tb ${STAGE} "${WORK}/stage_txn_tb.vvp"
               "-I;${WORK};-y;${WORK}/rtl;-Y;.sv;${PKGS};${WORK}/rec_import.sv;${WORK}/rtl/${module}.sv;${TB}"
               "+in=${DUMP}/${STAGE}.in.hex;+out=${DUMP}/${STAGE}.out.hex;+ctx=${ctx_file};+seed=${SEED}")
