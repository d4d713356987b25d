#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# run_fuzz.sh BUILD SECONDS RUNS JOBS TARGET...: runs each libFuzzer target BUILD/tests/fuzz/fuzz_<t>
# for SECONDS or until RUNS executions, whichever comes first (0 and -1: no limit), in JOBS
# processes (JOBS > 1: libFuzzer's -fork, which goes on past crashes and timeouts),
# seeded from tests/fuzz/corpus/<t> with the dictionary tests/fuzz/<t>.dict. New inputs go to
# BUILD/fuzz/corpus/<t>, kept for the next run; crashing inputs to BUILD/fuzz/artifacts/<t>/,
# the log to BUILD/fuzz/<t>.log. Prints per target the executions and crashes (a sanitizer
# report, a signal, an input running over 10 s or an exception the target lets through); exits
# 1 if any target crashed.
set -u
build=$1 seconds=$2 runs=$3 jobs=$4
shift 4
src=$(cd "$(dirname "$0")" && pwd)
total_crashes=0
for t in "$@"; do
  exe=$build/tests/fuzz/fuzz_$t
  [ -x "$exe" ] || { echo "fuzz: $exe is not built"; exit 2; }
  work=$build/fuzz
  mkdir -p "$work/corpus/$t" "$work/artifacts/$t"
  marker=$work/artifacts/$t/.started
  touch "$marker"
  fork=()
  [ "$jobs" -gt 1 ] && fork=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  start=$(date +%s)
  "$exe" "${fork[@]}" -max_total_time="$seconds" -runs="$runs" -timeout=10 -print_final_stats=1 -dict="$src/$t.dict" \
    -artifact_prefix="$work/artifacts/$t/" "$work/corpus/$t" "$src/corpus/$t" >"$work/$t.log" 2>&1
  rc=$?
  elapsed=$(($(date +%s) - start))
  if [ "$jobs" -gt 1 ]; then  # the parent's last status line: "#N: cov: ... exec/s ..."
    execs=$(grep -E '^#[0-9]+: cov:' "$work/$t.log" | tail -1 | sed -E 's/^#([0-9]+):.*/\1/')
  else
    execs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+)/\1/p' "$work/$t.log" | tail -1)
  fi
  artifacts=$(find "$work/artifacts/$t" -type f -newer "$marker" \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \))
  crashes=$(printf '%s' "$artifacts" | grep -c . || true)
  [ "$rc" -ne 0 ] && [ "$crashes" -eq 0 ] && crashes=1  # died without writing its input
  execs=${execs:-0}
  printf 'fuzz_%s: %s executions in %s s (%s/s), %s crashes\n' "$t" "$execs" "$elapsed" \
    "$((execs / (elapsed > 0 ? elapsed : 1)))" "$crashes"
  if [ "$crashes" -gt 0 ]; then
    echo "  log: $work/$t.log (exit $rc)"
    printf '%s\n' "$artifacts" | sed '/^$/d; s/^/  input: /' | head -5
  fi
  total_crashes=$((total_crashes + crashes))
done
[ "$total_crashes" -eq 0 ]
