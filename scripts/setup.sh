#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on the embedded
# default, leaving a report a person can open under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset default
cmake --build --preset default
bash scripts/main_job.sh out
