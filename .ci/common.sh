# Shared by the set-up scripts: install what is missing (as root or with sudo), then build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
JOBS="${JOBS:-$(nproc)}"

PACKAGES=(
  build-essential cmake pkg-config ccache clang-format
  libbullet-dev libosmesa6-dev libeigen3-dev libopencv-dev libyaml-cpp-dev
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  libgtest-dev libbenchmark-dev libcli11-dev libceres-dev zlib1g-dev
)
# The test command's fuzzing pass (bench/fuzz) also needs clang and its libFuzzer.
FUZZ_PACKAGES=(clang libclang-rt-14-dev)

# install_packages [more packages...]: PACKAGES and these.

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "coopmap: installing ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "coopmap: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# build DIR [cmake options...]
build() {
  local dir="$1"; shift
  cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" -j "$JOBS"
}
