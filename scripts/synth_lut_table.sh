#!/bin/bash
# Measured checkpoints of the LUT4 cost model (analysis/lut_model.hpp, docs/reports.md "LUT4 cost
# model"): one small module synthesised at a configuration that is not the default, with the
# generic flow of scripts/synth_divide.sh / synth_viewport.sh:
#   fxraster config --config CFG --emit-sv PKG; fxraster layout --config CFG --emit-records-sv REC
#   yosys: read_verilog -sv PKG REC rtl/<module and its submodules>; [chparam P TOP;]
#          synth -flatten -top TOP; abc -lut 4 -fast; opt_clean; stat; ltp -noff
# Usage: scripts/synth_lut_table.sh FXRASTER OUTDIR ROW...
#   ROW: NAME|TOP|CONFIG_JSON[|CHPARAM], e.g.
#   'div_r2_d24|fxr_div|{"div":{"num_bits":24,"den_bits":24}}'
#   'plane_w20|fxr_setup_plane|{}|-set AB 22 -set CWB 42 -set QB 26 -set OutBits 69'
# Runs Yosys under nice -n 19 with timeout ${SYNTH_TIMEOUT:-1200} s. Prints one JSON object per row:
#   {"name", "top", "config", "chparam", "lut4", "ff", "depth", "seconds", "command"}
# (lut4 null when Yosys failed or timed out). The rows of analysis/lut_table.json are its output.
set -euo pipefail
fxr=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
deps() {  # the module and every fxr_* module it instantiates, recursively
  local todo=("$1") seen=" " m
  while [ ${#todo[@]} -gt 0 ]; do
    m=${todo[0]}; todo=("${todo[@]:1}")
    case "$seen" in *" $m "*) continue ;; esac
    seen="$seen$m "
    for d in $(grep -oE '^\s*fxr_[a-z0-9_]+\s*(#|u_|[a-z_]+\s*\()' "$root/rtl/$m.sv" | grep -oE 'fxr_[a-z0-9_]+' | sort -u); do
      [ -f "$root/rtl/$d.sv" ] && todo+=("$d")
    done
  done
  for m in $seen; do echo -n " $root/rtl/$m.sv"; done
}
for row in "$@"; do
  IFS="|" read -r name top cfg chp <<< "$row"
  d="$out/$name"; mkdir -p "$d"
  python3 -c 'import json,sys; j=json.loads(sys.argv[1]); j["version"]=1; print(json.dumps(j))' "$cfg" > "$d/config.json"
  "$fxr" config --config "$d/config.json" --emit-sv "$d/fxr_config_pkg.sv" > /dev/null
  "$fxr" layout --config "$d/config.json" --emit-records-sv "$d/fxr_rec_pkg.sv" > /dev/null
  files=$(deps "$top")
  script="read_verilog -sv $d/fxr_config_pkg.sv $d/fxr_rec_pkg.sv $files; ${chp:+chparam $chp $top; }synth -flatten -top $top; abc -lut 4 -fast; opt_clean; tee -q -o $d/stat stat; tee -q -o $d/ltp ltp -noff"
  t0=$(date +%s)
  lut=null; ff=null; depth=null
  if nice -n 19 timeout "${SYNTH_TIMEOUT:-1200}" yosys -q -l "$d/log" -p "$script" > /dev/null 2>&1; then
    lut=$(awk '$1 == "$lut" {print $2}' "$d/stat" | tail -1)
    ff=$(awk '$1 ~ /^\$_.*DFF/ {s += $2} END {print s + 0}' "$d/stat")
    depth=$(sed -n 's/.*Longest topological path in \S* (length=\([0-9]*\)).*/\1/p' "$d/ltp" | tail -1)
  fi
  secs=$(( $(date +%s) - t0 ))
  cmd="scripts/synth_lut_table.sh build/app/fxraster OUT '$row'"
  python3 -c 'import json,sys; a=sys.argv; print(json.dumps({"name":a[1],"top":a[2],"config":json.loads(a[3]),"chparam":a[4],"lut4":json.loads(a[5]),"ff":json.loads(a[6]),"depth":json.loads(a[7] or "null"),"seconds":int(a[8]),"command":a[9]}))' \
    "$name" "$top" "$cfg" "$chp" "${lut:-null}" "${ff:-null}" "${depth:-null}" "$secs" "$cmd"
done
