#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_killed_writes.sh MESHMORPH MESH WORK: a run killed while it writes, by a signal that runs
# no handler (as kill -9), leaves its hidden temporary `.out.vtu.tmp-XXXXXX`; the next run
# that writes the same file removes it. The kill is SIGXFSZ under `ulimit -f 1`, which ends the
# process at its first write past 1 KiB: inside the write, every time.
set -u
mm=$1 mesh=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
temporaries() { find "$work" -name '.out.vtu.tmp-*' | wc -l; }

{ (ulimit -f 1; exec "$mm" --quiet convert "$mesh" "$work/out.vtu"); } 2> /dev/null
rc=$?
[ "$rc" -gt 128 ] || fail "the write was not killed (exit $rc)"
[ ! -e "$work/out.vtu" ] || fail "the killed run wrote out.vtu"
[ "$(temporaries)" = 1 ] || fail "the killed run left $(temporaries) temporaries, expected 1"

"$mm" --quiet convert "$mesh" "$work/out.vtu" || fail "the next run failed"
[ -s "$work/out.vtu" ] || fail "the next run wrote no out.vtu"
[ "$(temporaries)" = 0 ] || fail "the next run left the killed run's temporary"
echo "killed writes cleaned up"
