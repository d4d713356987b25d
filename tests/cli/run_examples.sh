#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# run_examples.sh MESHMORPH EXAMPLES WORK: `quality` and `convert` (every format, binary,
# MSH 2.2, order elevation) on every example mesh; each output is read back by `quality`,
# whose JSON report must keep the node and element counts (or the elevated node count).
set -eu
mm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
field() {  # field REPORT KEY: a top-level number or string of a report
  sed -n "s/^  \"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1"
}
check_same() {  # check_same WHAT EXPECTED ACTUAL
  [ "$2" = "$3" ] || { echo "FAIL: $1: expected $2, got $3"; exit 1; }
}
for mesh in "$examples"/meshes/*.msh; do
  name=$(basename "$mesh" .msh)
  "$mm" --quiet quality "$mesh" --json "$work/$name.json" -o "$work/${name}_quality.vtu" > "$work/$name.txt"
  grep -q "shape quality min / mean" "$work/$name.txt"
  check_same "$name method" quality "$(field "$work/$name.json" method)"
  check_same "$name valid" true "$(field "$work/$name.json" valid)"
  nodes=$(field "$work/$name.json" nodes)
  elements=$(field "$work/$name.json" elements)
  order=$(field "$work/$name.json" order)
  outputs="$name.vtu ${name}_bin.vtu ${name}_41.msh ${name}_41bin.msh ${name}_22.msh ${name}_22bin.msh"
  [ "$order" = 1 ] && outputs="$outputs $name.mesh"
  for out in $outputs; do
    flags=""
    case $out in *bin*) flags="--binary" ;; esac
    case $out in *_22*) flags="$flags --msh22" ;; esac
    # shellcheck disable=SC2086
    "$mm" --quiet convert "$mesh" "$work/$out" $flags
    "$mm" --quiet quality "$work/$out" --json "$work/$out.json" > /dev/null
    check_same "$out nodes" "$nodes" "$(field "$work/$out.json" nodes)"
    check_same "$out elements" "$elements" "$(field "$work/$out.json" elements)"
    check_same "$out min_shape_quality" "$(field "$work/$name.json" min_shape_quality)" \
      "$(field "$work/$out.json" min_shape_quality)"
  done
  if [ "$order" = 1 ]; then
    "$mm" --quiet convert "$mesh" "$work/${name}_p2.vtu" --order 2
    "$mm" --quiet quality "$work/${name}_p2.vtu" --json "$work/${name}_p2.json" > /dev/null
    check_same "${name}_p2 order" 2 "$(field "$work/${name}_p2.json" order)"
    check_same "${name}_p2 elements" "$elements" "$(field "$work/${name}_p2.json" elements)"
    [ "$(field "$work/${name}_p2.json" nodes)" -gt "$nodes" ] || { echo "FAIL: ${name}_p2 has no new nodes"; exit 1; }
  fi
  echo "ok $name: $nodes nodes, $elements elements, order $order"
done
