#!/usr/bin/env bash
# ellipsect's one entry point for a fresh Debian 12 machine.
#   bash scripts/run.sh example   install what is missing, build, run `ellipsect check` and
#                                 `ellipsect render` on a bundled scene
#   bash scripts/run.sh test      install what is missing, build, run the whole test suite
#                                 (Release build, then an ASan+UBSan build)
#   bash scripts/run.sh bench [NAME [ARGS]]   install what is missing, build, run
#                                 bench/bench_NAME (default: batch, ellipsect vs FCL and libccd)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake ninja-build pkg-config libeigen3-dev libhwy-dev libboost-dev libgtest-dev libgmock-dev libbenchmark-dev
          libfcl-dev libccd-dev libcli11-dev nlohmann-json3-dev librsvg2-bin)

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "==> installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

build() {  # build DIR [cmake args...]
  local dir=$1
  shift
  cmake -S . -B "$dir" -G Ninja "$@" >/dev/null
  cmake --build "$dir" -j "$(nproc)"
}

case "${1:-}" in
  example)
    install_missing
    build build/release -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=OFF -DELLIPSECT_BUILD_BENCH=OFF \
      -DELLIPSECT_BUILD_TOOLS=ON
    ./build/release/tools/ellipsect check examples/scenes/swept_2d.json
    ./build/release/tools/ellipsect render examples/scenes/swept_2d.json -o build/release/swept_2d.svg
    ./build/release/tools/ellipsect render examples/scenes/swept_2d.json -o build/release/swept_2d.png
    echo "==> picture of the first contact: build/release/swept_2d.svg (and swept_2d.png)"
    ;;
  test)
    install_missing
    # Options set explicitly: `example` may have configured build/release without tests.
    build build/release -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=ON -DELLIPSECT_BUILD_BENCH=ON \
      -DELLIPSECT_BUILD_TOOLS=ON
    (cd build/release && ctest --output-on-failure --no-tests=error -j "$(nproc)")
    # Sanitizer pass: same suite, fewer random cases per property test.
    build build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DELLIPSECT_SANITIZE=ON -DELLIPSECT_BUILD_TESTS=ON \
      -DELLIPSECT_BUILD_BENCH=OFF -DELLIPSECT_BUILD_TOOLS=ON
    (cd build/sanitize && ELLIPSECT_CASE_SCALE=0.05 ctest --output-on-failure --no-tests=error -j "$(nproc)")
    ;;
  bench)
    install_missing
    build build/release -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_BENCH=ON
    # bench [NAME [ARGS...]]: bench/bench_NAME.cpp (default: batch, the side-by-side with
    # FCL and libccd), with Google Benchmark's ARGS.
    program=build/release/bench/bench_${2:-batch}
    [[ -x $program ]] || { echo "no benchmark $program (see bench/)" >&2; exit 2; }
    "$program" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true "${@:3}"
    ;;
  *)
    echo "usage: bash scripts/run.sh example|test|bench [NAME [ARGS...]]" >&2
    exit 2
    ;;
esac
