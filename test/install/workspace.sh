#!/usr/bin/env bash
# rosmill built and installed the way ROS users do it, in a catkin workspace of its own: the package copied into
# WS/src/rosmill, built and installed by one of the workspace tools, then the source moved out of reach and the
# install space checked through its own setup.bash (check_install.sh). Prints the build's wall time. Each run is a
# full build of the package (several minutes on two cores), so CI checks the install of its own build instead
# (install_and_launch.sh); run this by hand after changing the build or the install rules.
# Usage: workspace.sh catkin_make|catkin_make_isolated|colcon [WS]   (WS: an empty folder, default a temporary one)
#   colcon: Debian's colcon with its ROS extension (packages colcon, python3-colcon-ros), installed when missing.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
tool="${1:?usage: workspace.sh catkin_make|catkin_make_isolated|colcon [WS]}"
ws="${2:-$(mktemp -d /tmp/rosmill-ws.XXXXXX)}"
mkdir -p "$ws/src/rosmill"
ws="$(cd "$ws" && pwd)"
jobs="${ROSMILL_JOBS:-$(nproc)}"

# The package as a user checks it out: the tracked files and the new ones, none of the build folders.
(cd "$root" && git ls-files -z --cached --others --exclude-standard | tar --null -T - -cf -) | tar -xf - -C "$ws/src/rosmill"

case "$tool" in
  catkin_make)
    build=(catkin_make install -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$jobs")
    install="$ws/install" ;;
  catkin_make_isolated)
    build=(catkin_make_isolated --install -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$jobs")
    install="$ws/install_isolated" ;;
  colcon)
    need=()
    for p in colcon python3-colcon-ros python3-colcon-cmake python3-colcon-bash python3-colcon-package-information; do
      dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
    done
    if [ ${#need[@]} -gt 0 ]; then
      sudo_cmd=()
      [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
      echo "workspace.sh: installing ${need[*]}"
      DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
    fi
    # One merged install space, as catkin's: install/setup.bash (colcon's) brings in the package's environment.
    # colcon-ros builds a catkin package's `tests` target too unless told not to.
    build=(colcon build --merge-install --catkin-skip-building-tests
           --cmake-args -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3)
    export MAKEFLAGS="-j$jobs"
    install="$ws/install" ;;
  *) echo "workspace.sh: unknown tool '$tool' (catkin_make, catkin_make_isolated or colcon)" >&2; exit 2 ;;
esac

echo "workspace.sh: $tool in $ws"
start=$(date +%s)
(cd "$ws" && env -u CMAKE_PREFIX_PATH -u ROS_PACKAGE_PATH "${build[@]}") >"$ws/build.log" 2>&1 \
  || { tail -40 "$ws/build.log"; echo "workspace.sh: $tool failed (log: $ws/build.log)" >&2; exit 1; }
seconds=$(( $(date +%s) - start ))
programs=$(find "$ws" -path "$ws/src" -prune -o -type f -name 'test_*' -perm -u+x -print | wc -l)
echo "workspace.sh: $tool built and installed in $seconds s; test programs built: $programs"
[ "$programs" -eq 0 ] || { echo "workspace.sh: the workspace build compiled test programs" >&2; exit 1; }

# The source out of reach while the install is checked; put back afterwards.
mv "$ws/src" "$ws/src.away"
trap 'mv "$ws/src.away" "$ws/src"' EXIT
bash "$here/check_install.sh" "$install"
