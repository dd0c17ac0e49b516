#!/usr/bin/env bash
# Installs the Debian 12 packages dynrad needs, and does nothing when they are present.
# Safe to run repeatedly; needs root (or sudo).
#
#   scripts/install-deps.sh build   # building and running dynrad: compiler, CMake, Ninja,
#                                   # pkg-config, the -dev libraries (cairo draws the PDF
#                                   # report), the DejaVu font (the grids' pictures) and
#                                   # three.js (libjs-three, inlined in `dynrad view`'s
#                                   # pages) (scripts/demo.sh)
#   scripts/install-deps.sh [all]   # also what the tests and CI need: GoogleTest, Google
#                                   # Benchmark, MeshLab and Xvfb (viewer test), Blender
#                                   # (add-on test), Chromium (the walk-through page's
#                                   # test), clang, libclang-rt-dev (libFuzzer and
#                                   # sanitizer runtimes) and llvm (llvm-symbolizer, for
#                                   # readable sanitizer stacks) for scripts/fuzz.sh and
#                                   # scripts/test-sanitizers.sh, poppler-utils (pdfinfo,
#                                   # pdftotext: the PDF report's test), pybind11, the
#                                   # Python headers and venv (`import dynrad` and its
#                                   # pip install test)
#
# DRY_RUN=1 prints the packages that would be installed and installs nothing.
set -euo pipefail

mode=${1:-all}
build_packages=(
  build-essential cmake ninja-build pkg-config
  libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libembree-dev libtbb-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libtinyobjloader-dev libpng-dev libtinygltf-dev
  libassimp-dev libjs-three
  libfreetype-dev fonts-dejavu-core libcairo2-dev
)
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev
  meshlab xvfb xauth
  blender python3-numpy assimp-testmodels
  pybind11-dev python3-dev python3-venv
  chromium
  clang libclang-rt-dev llvm
  poppler-utils
)
case $mode in
  build) packages=("${build_packages[@]}") ;;
  all) packages=("${build_packages[@]}" "${test_packages[@]}") ;;
  *)
    echo "usage: $0 [build|all]   (build: what building and running dynrad needs; all, the default: also tests and CI)" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps ($mode): all ${#packages[@]} packages present"
  exit 0
fi
if [ -n "${DRY_RUN:-}" ]; then
  echo "install-deps ($mode): would install ${missing[*]}"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install-deps ($mode): installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
