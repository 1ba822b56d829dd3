# Shared set-up for scripts/demo, scripts/test and .ci/run (sourced, not run):
# installs missing Debian packages, configures and builds. Idempotent: a second
# run with nothing changed only asks ninja, which has nothing to do.
set -euo pipefail
OCCLUDE_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# Required to build and test, plus the optional peers of `occlude bench`: FCL, and OpenVDB
# (whose headers also need Boost's, which libopenvdb-dev does not pull in). The peers are here,
# not in the test lane's list, so that a build/ configured by scripts/demo and then tested by
# scripts/test has them too (it is not configured again).
OCCLUDE_PACKAGES=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libnlopt-cxx-dev libceres-dev libassimp-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev zlib1g-dev
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libfcl-dev libopenvdb-dev libboost-dev
  libjs-three
)
# The test lane only: headless Chromium for the viewer's browser tests (app_viewer_tests;
# they skip, saying why, without it). scripts/test adds it.
OCCLUDE_TEST_PACKAGES=(chromium)

occlude_install_deps() {
  local missing=() p
  for p in "${OCCLUDE_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  echo "occlude: installing missing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "occlude: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# occlude_build DIR [cmake options...]: configure once, then build incrementally
# (everything, or only $OCCLUDE_TARGET when that is set).
occlude_build() {
  local dir="$OCCLUDE_ROOT/$1"
  shift
  local stamp="$dir/.occlude-configure-args"
  if [ ! -f "$dir/build.ninja" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$*" ]; then
    echo "occlude: configuring $dir ($*)"
    cmake -S "$OCCLUDE_ROOT" -B "$dir" -G Ninja "$@"
    echo "$*" >"$stamp"
  fi
  echo "occlude: building $dir"
  cmake --build "$dir" -j"$(nproc)" ${OCCLUDE_TARGET:+--target "$OCCLUDE_TARGET"}
}
