#!/usr/bin/env bash
# An install space checked as a ROS user meets it: in an environment that has only the system's ROS and what the
# install's own setup.bash adds (no devel space, no source folder), rospack finds the package there, the installed
# `rosmill` tool runs, the Python messages import, demo.launch resolves, `roslaunch rosmill bridge.launch` starts the
# installed node with the installed configuration, rosrun starts the installed planner, and SIGINT stops each
# by itself (within 10 s, before roslaunch would escalate).
# Usage: check_install.sh PREFIX [SETUP_DIR]   (SETUP_DIR: where setup.bash is, default PREFIX)
set -euo pipefail
prefix="$(cd "$1" && pwd)"
setup_dir="$(cd "${2:-$1}" && pwd)"
work="$(mktemp -d /tmp/rosmill-install-run.XXXXXX)"
launch_pid=""
cleanup() {
  [ -n "$launch_pid" ] && kill -9 "$launch_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "install check: FAILED: $*" >&2; exit 1; }

for f in bin/rosmill bin/rosmill-full lib/rosmill/gcode_bridge lib/rosmill/toolpath_planner lib/rosmill/stl_loader \
         share/rosmill/package.xml share/rosmill/launch/bridge.launch share/rosmill/launch/demo.launch \
         share/rosmill/config/machine.yaml share/rosmill/config/tools.yaml share/rosmill/config/rosmill.rviz \
         include/rosmill/gcode/prepare_program.hpp share/rosmill/msg/ProgramStatus.msg \
         share/rosmill/action/RunProgram.action; do
  [ -e "$prefix/$f" ] || fail "the install has no $f"
done
ls "$prefix"/include/rosmill/*.h >/dev/null 2>&1 || fail "the install has no generated message headers"
ls "$prefix"/lib/rosmill/*.a "$prefix"/lib/*.a >/dev/null 2>&1 || ls "$prefix"/lib/lib*.a >/dev/null 2>&1 \
  || fail "the install has no libraries"

[ -f "$setup_dir/setup.bash" ] || fail "$setup_dir has no setup.bash"

# Only the install (through its setup.bash) and the system's ROS are visible from here on.
port=$((20000 + RANDOM % 20000))
printf '#!/usr/bin/env bash\nsource "%s/setup.bash"\nexec "$@"\n' "$setup_dir" >"$work/in_install"
chmod +x "$work/in_install"
clean_env=(env -i HOME="$work" PATH="/usr/bin:/bin" ROS_HOME="$work/ros" ROS_MASTER_URI="http://localhost:$port"
           ROS_HOSTNAME=localhost "$work/in_install")
"${clean_env[@]}" rospack find rosmill | grep -qx "$prefix/share/rosmill" || fail "rospack does not find the install"
(cd "$work" && "${clean_env[@]}" rosmill primitive cube -o "$work/cube.stl" >/dev/null) || fail "installed rosmill"
[ "$("${clean_env[@]}" which rosmill)" = "$prefix/bin/rosmill" ] || fail "rosmill on PATH is not the install's"
"${clean_env[@]}" python3 -c "import sys, rosmill.msg, rosmill.srv
from rosmill.msg import ProgramStatus, PlanJobAction
sys.exit(not rosmill.msg.__file__.startswith('$prefix/'))" || fail "the install's Python messages do not import"
"${clean_env[@]}" roslaunch --nodes rosmill demo.launch stl:=primitive:cube bridge:=true >"$work/demo_nodes.txt" 2>&1 \
  || { cat "$work/demo_nodes.txt"; fail "demo.launch does not resolve from the install"; }
for node in stl_loader segmenter slicer toolpath_planner gcode_bridge; do
  grep -qx "/rosmill/$node" "$work/demo_nodes.txt" || fail "demo.launch from the install has no $node"
done

"${clean_env[@]}" roslaunch -p "$port" rosmill bridge.launch controller:="file://$work" program_dir:="$work/programs" \
  >"$work/launch.log" 2>&1 &
launch_pid=$!
up=""
for _ in $(seq 1 150); do
  if "${clean_env[@]}" rosnode list 2>/dev/null | grep -qx /rosmill/gcode_bridge &&
     "${clean_env[@]}" rosservice list 2>/dev/null | grep -qx /rosmill/gcode_bridge/start; then up=1; break; fi
  kill -0 "$launch_pid" 2>/dev/null || break
  sleep 0.2
done
[ -n "$up" ] || { cat "$work/launch.log"; fail "the installed bridge did not come up"; }
machine=$("${clean_env[@]}" rosparam get /rosmill/gcode_bridge/machine)
[ "$machine" = "$prefix/share/rosmill/config/machine.yaml" ] ||
  fail "machine parameter is '$machine', not the install's"

# Every node stops by itself on SIGINT, well before roslaunch would escalate to SIGTERM (15 s after SIGINT): within
# 10 s, which a loaded machine does not reach by chance (idle, it takes 0.3-0.6 s). Prints the milliseconds taken.
stop_on_sigint() {
  local name="$1" pid="$2" start ms
  start=$(date +%s%N)
  kill -INT "$pid"
  for _ in $(seq 1 200); do kill -0 "$pid" 2>/dev/null || break; sleep 0.05; done
  kill -0 "$pid" 2>/dev/null && fail "$name still runs 10 s after SIGINT"
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  echo "$ms"
}

# The installed planner, started by rosrun (which finds the install's nodes) against the same master with the
# installed tool table; rosrun execs the node, so the pid is the node's.
(cd "$work" && exec "${clean_env[@]}" rosrun rosmill toolpath_planner \
   _tool_table:="$prefix/share/rosmill/config/tools.yaml" >"$work/planner.log" 2>&1) &
planner_pid=$!
for _ in $(seq 1 150); do
  "${clean_env[@]}" rosservice list 2>/dev/null | grep -qx /plan && break
  kill -0 "$planner_pid" 2>/dev/null || { cat "$work/planner.log"; fail "the installed planner stopped"; }
  sleep 0.2
done
planner_ms=$(stop_on_sigint toolpath_planner "$planner_pid")

node_pid=$(pgrep -f "$prefix/lib/rosmill/gcode_bridge" | head -1)
[ -n "$node_pid" ] || fail "no gcode_bridge process from the install"
bridge_ms=$(stop_on_sigint gcode_bridge "$node_pid")
kill -INT "$launch_pid"; wait "$launch_pid" 2>/dev/null || true; launch_pid=""
echo "install check: $prefix works through $setup_dir/setup.bash; after SIGINT the planner stopped in $planner_ms ms," \
     "the bridge in $bridge_ms ms"
