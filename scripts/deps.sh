# Sourced by scripts/run and scripts/test: installs the Debian packages cablelab needs.
# Idempotent and quiet: when every package is present it only runs dpkg-query.
CABLELAB_PACKAGES=(
  cmake g++ make pkg-config
  libbox2d-dev libeigen3-dev nlohmann-json3-dev libcli11-dev libpng-dev
  libgtest-dev libbenchmark-dev libmujoco-dev
  libsdl2-dev libimgui-dev libstb-dev libosmesa6-dev libgif-dev
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  xvfb xauth
  python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
  python3-venv python3-pip python3-setuptools python3-wheel python3-mypy python3-distributed
  python3-jsonschema
)

cablelab_install_deps() {
  local missing=()
  for p in "${CABLELAB_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "cablelab: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq >/dev/null
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

cablelab_build() {
  local dir=${1:-build}; shift || true
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" -j"$(nproc)" 2>&1 | grep -E "error|warning|Error" || true
  cmake --build "$dir" -j"$(nproc)" >/dev/null
}
