#!/usr/bin/env bash
# The second test command (docs/testing.md): a clang-14 build with AddressSanitizer and
# UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the first report fails the test; clang
# includes float-cast-overflow) in build-sanitize/, running the model, tools, sc and peer labels,
# the committed fuzz corpora and a short deterministic libFuzzer run of every harness (label fuzz).
# The RTL testbenches are left out (FXR_RTL=OFF): Verilator's generated code is not the model's.
# Only Mesa's own known leak in OSMesa is suppressed, by library name (scripts/lsan.supp).
# Extra arguments go to ctest, e.g. `bash scripts/sanitize.sh -L fuzz`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset sanitize
cmake --build --preset sanitize
if [ $# -eq 0 ]; then set -- -L 'model|tools|sc|peer|fuzz' -LE slow; fi
ctest --preset sanitize "$@"
