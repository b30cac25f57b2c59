#!/usr/bin/env bash
# The cell-recording template used as a cell's CI would use it: rosmill installed from the build CI made (as
# install_and_launch.sh does), a new catkin package `my_cell` in a workspace of its own that depends on it, with the
# template copied from the install (share/rosmill/templates/cell_recording.test), a recording, a part and a job
# beside it, built and run by `catkin_make run_tests` and judged by `catkin_test_results`:
#   1. as the template comes (its scans fused where tf puts them: the recording's tf is exact): every expectation
#      met, catkin_test_results passes;
#   2. with an RMS bound the recording cannot meet (max_rms_mm: 0.001): catkin_test_results fails, and the failure
#      names the bound (the test case and its message in rostest's XML).
# Usage: cell_package.sh BUILD_DIR BAG PART.stl JOB.yaml   (the job's `part:` is rewritten to the copied part)
set -euo pipefail
build="$(cd "$1" && pwd)"
bag="$2" part="$3" job="$4"
work="$(mktemp -d /tmp/rosmill-cell-package.XXXXXX)"
trap 'rm -rf "$work"' EXIT
fail() { echo "cell package test: FAILED: $*" >&2; exit 1; }

configured=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
DESTDIR="$work/root" cmake --install "$build" >"$work/install.log" 2>&1 || { cat "$work/install.log"; fail "install"; }
prefix="$work/root$configured"
template="$prefix/share/rosmill/templates/cell_recording.test"
[ -f "$template" ] || fail "the install has no $template"

# The cell's own package, as its README tells a user to make it.
pkg="$work/ws/src/my_cell"
mkdir -p "$pkg/test/recordings"
cat >"$pkg/package.xml" <<'EOF'
<?xml version="1.0"?>
<package format="2">
  <name>my_cell</name>
  <version>0.0.1</version>
  <description>A cell that tests rosmill on its own recordings.</description>
  <maintainer email="cell@example.com">cell</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <test_depend>rostest</test_depend>
  <test_depend>rosmill</test_depend>
</package>
EOF
cat >"$pkg/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.10)
project(my_cell)
find_package(catkin REQUIRED)
catkin_package()
if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/cell_recording.test)
endif()
EOF
cp "$template" "$pkg/test/cell_recording.test"
cp "$bag" "$pkg/test/recordings/cell.bag"
cp "$part" "$pkg/test/part.stl"
sed 's#^part: .*#part: part.stl#' "$job" >"$pkg/test/job.yaml"
# The recording's tf is exact (a synthetic one): this cell fuses its scans where tf puts them.
sed -i 's#<arg name="refine_views" default="true"#<arg name="refine_views" default="false"#' "$pkg/test/cell_recording.test"
grep -q 'name="refine_views" default="false"' "$pkg/test/cell_recording.test" || fail "could not set refine_views in the copy"

# Only the system's ROS and rosmill's install (through its setup.bash) are visible to the workspace.
port=$((20000 + RANDOM % 20000))
in_env=(env -i HOME="$work" PATH="/usr/bin:/bin" ROS_HOME="$work/ros" ROS_HOSTNAME=localhost
        ROS_MASTER_URI="http://localhost:$port" ROSCONSOLE_STDOUT_LINE_BUFFERED=1 bash -c)
run_tests() {  # LOG: catkin_make run_tests, then catkin_test_results' exit status
  "${in_env[@]}" "source '$prefix/setup.bash' && cd '$work/ws' &&
    catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 run_tests && catkin_test_results build/test_results" >"$1" 2>&1
}

start=$(date +%s)
run_tests "$work/pass.log" || { tail -60 "$work/pass.log"; fail "the template as it comes does not pass"; }
echo "cell package test: the template passes from a new package ($(( $(date +%s) - start )) s):"
grep -E "^Summary|tests, [0-9]+ errors" "$work/pass.log" | tail -2 | sed 's/^/  /'

sed -i 's/max_rms_mm: 0.05 /max_rms_mm: 0.001/' "$pkg/test/cell_recording.test"
grep -q "max_rms_mm: 0.001" "$pkg/test/cell_recording.test" || fail "could not tighten max_rms_mm in the copy"
rm -rf "$work/ws/build/test_results"
if run_tests "$work/fail.log"; then tail -40 "$work/fail.log"; fail "a bound the recording cannot meet passes"; fi
xml=$(find "$work/ws/build/test_results" -name '*.xml' -print | xargs grep -l "max_rms_mm" || true)
[ -n "$xml" ] || { tail -40 "$work/fail.log"; fail "no test result names max_rms_mm"; }
grep -q 'FitAndUncertaintyWithinBounds' $xml || fail "the failing case is not FitAndUncertaintyWithinBounds"
echo "cell package test: with max_rms_mm 0.001 it fails, saying:"
grep -o "the fit's RMS (mm) [^;]*" $xml | head -1 | sed 's/^/  /'
