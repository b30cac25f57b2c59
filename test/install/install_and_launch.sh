#!/usr/bin/env bash
# The install from the build CI made (no second build): `cmake --install` of it into an empty folder, as catkin_make
# install does, then checked through its own setup.bash with the source tree out of reach (check_install.sh).
# Usage: install_and_launch.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="$1"
# Into an empty folder by DESTDIR, at the configured prefix below it: catkin writes the install's setup.bash to the
# prefix given at configure time (a workspace's install/), which --prefix at install time does not move.
destdir="$(mktemp -d /tmp/rosmill-install.XXXXXX)"
trap 'rm -rf "$destdir"' EXIT
configured=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
DESTDIR="$destdir" cmake --install "$build" >"$destdir.log" 2>&1 \
  || { cat "$destdir.log"; rm -f "$destdir.log"; echo "install test: FAILED: cmake --install" >&2; exit 1; }
rm -f "$destdir.log"
bash "$here/check_install.sh" "$destdir$configured"
