# Shared by the scripts/ entry points: environment fixes and the catkin workspace. Source, don't run.
# shellcheck shell=bash
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# Debian's ROS lives under /usr; a pyenv python3 earlier on PATH lacks the ROS modules (notes: pitfall 1).
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export ROS_PYTHON_VERSION=3
export PYTHONNOUSERSITE=1
unset PYTHONPATH PYENV_VERSION || true

log() { printf '\033[1m[%s]\033[0m %s\n' "$(basename "$0")" "$*" >&2; }

# Workspace kept in a git-ignored folder, the package linked into its src/.
# In build/.ws: rosrun searches the package folder but skips build/ (elsewhere every tool would appear twice
# and rosrun refuse to choose), and roslaunch/rostest's search skips hidden folders (elsewhere it would loop
# forever through the workspace's link back to the package).
ws_dir() { echo "$REPO/build/.ws${WS_SUFFIX:-}"; }

ws_build() {  # ws_build [extra cmake args...]
  local ws; ws="$(ws_dir)"
  mkdir -p "$ws/src"
  [ -L "$ws/src/offshore_gnc" ] || ln -sfn "$REPO" "$ws/src/offshore_gnc"
  local jobs; jobs="$(nproc)"
  # One compiler cache per user, shared by every checkout: paths are taken relative to the checkout (BASEDIR) and the
  # build directory is not hashed, so a fresh clone (CI's, a helper's) reuses what any other checkout compiled.
  export CCACHE_DIR="${CCACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/offshore_gnc-ccache}"
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$REPO}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  local first=0
  [ -f "$ws/build/CMakeCache.txt" ] || first=1
  ( cd "$ws" && catkin_make -j"$jobs" \
      -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
      -DCATKIN_ENABLE_TESTING=ON "$@" ) >"$ws/build.log" 2>&1 || {
    tail -n 60 "$ws/build.log" >&2; log "build failed (full log: $ws/build.log)"; return 1; }
  if [ $first = 1 ]; then
    # setup_cached.sh is written before devel/lib exists on the first configure (notes: pitfall 2).
    ( cd "$ws" && catkin_make --force-cmake -j"$jobs" "$@" ) >>"$ws/build.log" 2>&1 || {
      tail -n 60 "$ws/build.log" >&2; log "build failed (full log: $ws/build.log)"; return 1; }
  fi
  if grep -E "warning:" "$ws/build.log" | grep -F "$REPO" >/dev/null 2>&1; then
    log "compiler warnings in project code:"; grep -E "warning:" "$ws/build.log" | grep -F "$REPO" | sort -u >&2 || true
  fi
}

ws_source() {
  # shellcheck disable=SC1091
  set +u; source "$(ws_dir)/devel/setup.bash"; set -u
}
