#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# check_mpi_optimize.sh MPIEXEC MESHMORPH EXAMPLES DATA WORK: `mpirun -n N meshmorph optimize`
# on 1, 2 and 3 ranks (docs/parallel.md). The 2D annulus (triangles) and the 3D sphere in a box
# (tetrahedra) on 2 and 3 ranks, the P2 sphere in a box and the hybrid layer (tetrahedra,
# hexahedra, prisms, pyramids) on 2, boundary fixed: the nodes within 1e-10 of the bounding box's
# diagonal of the 1-rank result and the report's figures within 1e-9 (compare_runs.py); two
# runs on the same number of ranks write the same bytes. Bad input on 2 ranks: exit 2, the
# message once, nothing written. A failure of rank 0 alone (an output it cannot write), and one of rank 2 while the
# others wait for it (MESHMORPH_FAIL_ON_RANK): every rank ends with exit 2.
# Sliding boundaries: exit 2 on ranks. Other commands run on rank 0 alone: `quality` prints its
# table once.
set -u
mpiexec=$1 mm=$2 examples=$3 data=$4 work=$5
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
flags=()
# Open MPI ("mpiexec (OpenRTE) 4.1.4 ... open-mpi.org")
"$mpiexec" --version 2>&1 | grep -q -i -e "OpenRTE" -e "open-mpi" && flags=(--oversubscribe --allow-run-as-root)
# Ranks that wait in MPI yield their core (Open MPI spins otherwise), as the tests share 2 cores.
export OMPI_MCA_mpi_yield_when_idle=1
ranks() {  # ranks N ARGS...: meshmorph on N ranks
  local n=$1
  shift
  timeout 300 "$mpiexec" "${flags[@]}" -n "$n" "$mm" "$@"
}

# mesh, its folder, and the rank counts to compare with one rank
cases=("annulus $examples/meshes 2 3" "sphere_in_box $examples/meshes 2 3" "sphere_in_box_p2 $examples/meshes 2"
       "hybrid_layer $data 2")
for c in "${cases[@]}"; do
  read -r mesh folder counts <<< "$c"
  for n in 1 $counts; do
    ranks $n optimize "$folder/$mesh.msh" --quiet -o "$work/${mesh}_$n.msh" --report "$work/${mesh}_$n.json" \
      > "$work/${mesh}_$n.out" 2> "$work/${mesh}_$n.err" || fail "$mesh on $n ranks: exit $?: $(cat "$work/${mesh}_$n.err")"
    grep -q '"ranks": '$n "$work/${mesh}_$n.json" || fail "$mesh on $n ranks: the report has no \"ranks\": $n"
  done
  grep -q '"converged": true' "$work/${mesh}_1.json" || fail "$mesh: not converged on one rank"
  for n in $counts; do
    /usr/bin/python3 "$here/compare_runs.py" "$work/${mesh}_1.msh" "$work/${mesh}_1.json" "$work/${mesh}_$n.msh" \
      "$work/${mesh}_$n.json" || fail "$mesh: $n ranks against 1"
  done
done
grep -q '"partitioner": "ptscotch"' "$work/annulus_3.json" || fail "annulus: not partitioned by PT-Scotch"

# A fixed rank count gives the same bits (the partition and GAMG's products included).
ranks 3 optimize "$examples/meshes/annulus.msh" --quiet -o "$work/again.msh" > /dev/null 2>&1 || fail "again: exit $?"
cmp -s "$work/again.msh" "$work/annulus_3.msh" || fail "two runs of the annulus on 3 ranks differ"
ranks 2 optimize "$examples/meshes/sphere_in_box.msh" --quiet -o "$work/again.msh" > /dev/null 2>&1 || fail "again: exit $?"
cmp -s "$work/again.msh" "$work/sphere_in_box_2.msh" || fail "two runs of the sphere on 2 ranks differ"

# Bad input: exit 2, said once, nothing written.
ranks 2 optimize "$work/missing.msh" -o "$work/missing_out.msh" > "$work/missing.out" 2> "$work/missing.err"
rc=$?
[ "$rc" = 2 ] || fail "missing mesh: exit $rc, expected 2"
[ "$(grep -c 'meshmorph: error:.*missing.msh' "$work/missing.err")" = 1 ] || fail "missing mesh: not said once: $(cat "$work/missing.err")"
[ ! -e "$work/missing_out.msh" ] || fail "missing mesh: an output was written"

# Sliding boundaries do not run on ranks yet: said, exit 2.
ranks 2 optimize "$examples/meshes/annulus.msh" --boundary slide -o "$work/slide.msh" > /dev/null 2> "$work/slide.err"
rc=$?
[ "$rc" = 2 ] && grep -q "do not run on MPI ranks yet" "$work/slide.err" || fail "slide on 2 ranks: exit $rc: $(cat "$work/slide.err")"
[ ! -e "$work/slide.msh" ] || fail "slide on 2 ranks: an output was written"

# Rank 0 cannot write its output (its folder is a file): every rank ends with rank 0's code.
touch "$work/not_a_folder"
ranks 3 optimize "$examples/meshes/annulus.msh" --quiet -o "$work/not_a_folder/out.msh" > /dev/null 2> "$work/unwritable.err"
rc=$?
[ "$rc" = 2 ] || fail "unwritable output: exit $rc, expected 2: $(cat "$work/unwritable.err")"
[ "$(grep -c 'meshmorph: error:' "$work/unwritable.err")" = 1 ] || fail "unwritable output: not said once: $(cat "$work/unwritable.err")"

# Rank 2 fails while the others wait for it in collective calls: all end, with its exit code.
MESHMORPH_FAIL_ON_RANK=2 ranks 3 optimize "$examples/meshes/annulus.msh" --quiet -o "$work/injected.msh" \
  > /dev/null 2> "$work/injected.err"
rc=$?
[ "$rc" = 2 ] || fail "failure on rank 2: exit $rc, expected 2: $(cat "$work/injected.err")"
grep -q 'rank 2: a failure injected' "$work/injected.err" || fail "failure on rank 2: not said: $(cat "$work/injected.err")"
[ ! -e "$work/injected.msh" ] || fail "failure on rank 2: an output was written"

# A command that does not run on ranks yet runs on rank 0 alone.
ranks 2 quality "$examples/meshes/annulus.msh" > "$work/quality.out" 2>&1 || fail "quality on 2 ranks: exit $?"
[ "$(grep -c '^mesh ' "$work/quality.out")" -le 1 ] && [ "$(grep -c 'triangle' "$work/quality.out")" -ge 1 ] \
  && [ "$(sort "$work/quality.out" | uniq -d | wc -l)" = 0 ] || fail "quality on 2 ranks: $(cat "$work/quality.out")"
echo "ok"
