#!/usr/bin/env bash
# ellipsect's one entry point for a fresh Debian 12 machine.
#   bash scripts/run.sh example   install what is missing, build, run `ellipsect check` and
#                                 `ellipsect render` on a bundled scene
#   bash scripts/run.sh test      install what is missing, build, run the whole test suite
#                                 (Release build, the demo page's browser test, the Python
#                                 package's tests, then the sanitized build's tests and
#                                 every fuzz target on its kept inputs and corpus and a
#                                 short seeded mutation run, then the suites on the
#                                 emulated wide type of narrow-long-double platforms)
#   bash scripts/run.sh fuzz [NAME [SECONDS]]   the long run of one fuzz target or all
#                                 (default 600 s each; docs/fuzzing.md)
#   bash scripts/run.sh bench [NAME [ARGS]]   install what is missing, build, run
#                                 bench/bench_NAME (default: batch, ellipsect vs FCL and libccd)
#   bash scripts/run.sh demo [PORT]   build the demo page (WebAssembly) and serve it on
#                                 http://127.0.0.1:PORT/ (default 8000)
#   bash scripts/run.sh web       the page's browser test alone (`test` runs it too)
set -euo pipefail
cd "$(dirname "$0")/.."

# The packages each command needs. `example` needs the C++ set alone (the library, the program
# and its picture); the others add the test, benchmark, page and Python sets.
cxx_packages=(g++ cmake ninja-build ccache pkg-config libeigen3-dev libhwy-dev libboost-dev libgmp-dev libcli11-dev
              nlohmann-json3-dev librsvg2-bin)
packages=("${cxx_packages[@]}" libgtest-dev libgmock-dev libbenchmark-dev libfcl-dev libccd-dev libcgal-dev libopencv-dev
          clang libclang-rt-14-dev)
# The engines whose ellipsoid narrow phase ellipsect replaces (modules/mujoco, modules/bullet;
# docs/engines.md): optional in the build, installed here so that their tests run.
packages+=(libmujoco-dev libbullet-dev)
# ---- web (the demo page, web/): Emscripten, Chromium for its browser test, Node and npm
# for playwright-core. npm only where no npm is on the PATH (a Node from elsewhere bundles
# its own, and Debian's npm would conflict with it).
packages+=(emscripten chromium nodejs)
command -v npm >/dev/null || packages+=(npm)
# ---- end web
# The Python package (python/, python_test below): built by setuptools through CMake.
packages+=(python3-dev python3-venv python3-pip python3-setuptools python3-wheel python3-pybind11 python3-numpy
           python3-pytest python3-hypothesis python3-mpmath python3-matplotlib python3-dask python3-distributed
           python3-pandas python3-shapely python3-skimage python3-torch mypy)

install_missing() {  # install_missing [PACKAGE...] (default: every package above)
  local missing=() p
  [ $# -gt 0 ] || set -- "${packages[@]}"
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "==> installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

# The compiler cache (ccache): every build below compiles through it, in ~/.cache/ccache
# (CCACHE_DIR elsewhere). Paths under the checkout are hashed relative to it, and the
# working directory is not hashed, so a fresh clone in another folder reuses what an
# earlier build of the same code compiled on this machine. The precompiled headers of the
# tests are cached too (ccache's pch sloppiness; clang's without their timestamp,
# tests/CMakeLists.txt).
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1 CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-8G}
export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# build DIR [--target TARGET...] [cmake args...]. The Python module is left to pip
# (python_test), which builds it in the Release tree.
build() {
  local dir=$1 targets=()
  shift
  while [ "${1:-}" = --target ]; do targets+=(--target "$2"); shift 2; done
  cmake -S . -B "$dir" -G Ninja -DELLIPSECT_BUILD_PYTHON=OFF "${launcher[@]}" "$@" >/dev/null
  cmake --build "$dir" -j "$(nproc)" "${targets[@]}"
}

step() { echo "==> [$((SECONDS / 60)) min $((SECONDS % 60)) s] $*"; }

# The sanitized build, build/sanitize: clang with ASan and UBSan, line tables for their
# reports, and libFuzzer's coverage instrumentation, so that the tests and the fuzz targets
# (fuzz/) share one build of the library (CMakeLists.txt), its files compiled in batches
# (ELLIPSECT_UNITY_LIBRARY). build_sanitized [TARGET...]
build_sanitized() {
  # A tree configured by another compiler is rebuilt from scratch.
  if [ -f build/sanitize/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build/sanitize/CMakeCache.txt; then
    rm -rf build/sanitize
  fi
  cmake -S . -B build/sanitize -G Ninja -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" -DELLIPSECT_SANITIZE=ON \
    -DELLIPSECT_BUILD_FUZZ=ON -DELLIPSECT_BUILD_TESTS=ON -DELLIPSECT_BUILD_BENCH=OFF -DELLIPSECT_BUILD_TOOLS=ON \
    -DELLIPSECT_UNITY_LIBRARY=ON >/dev/null
  cmake --build build/sanitize -j "$(nproc)" ${1:+--target} "$@"
}

fuzz_targets() {
  local f
  for f in fuzz/*_fuzz.cpp; do
    f=${f#fuzz/}
    echo "${f%_fuzz.cpp}"
  done
}

# fuzz_check NAME: every kept input of fuzz/regressions/NAME/, each run once (no mutation:
# docs/fuzzing.md says why); the corpus is run by fuzz_mutate, which starts with every file
# of it. A failing input is written to build/sanitize/artifacts/.
fuzz_check() {
  local name=$1 program=build/sanitize/fuzz/fuzz_$1 log f inputs=() artifacts=build/sanitize/artifacts/
  for f in fuzz/regressions/"$name"/*; do [ -f "$f" ] && inputs+=("$f"); done
  mkdir -p "$artifacts"
  echo "==> fuzz_$name: ${#inputs[@]} kept inputs"
  [ ${#inputs[@]} -gt 0 ] || return 0  # with no file named, libFuzzer would start mutating
  log=$("$program" -timeout=30 -artifact_prefix="$artifacts" "${inputs[@]}" 2>&1) || { echo "$log"; return 1; }
}

# fuzz_mutate NAME RUNS: every file of the committed corpus fuzz/corpus/NAME/, then a short
# mutation run that tries the same inputs on every machine and in every clone: seed 1, RUNS
# executions in one process (the corpus's included), from a copy of the corpus, the batch
# functions pinned to the portable SIMD target (their coverage would otherwise follow the
# CPU), no mutations from the operands of traced comparisons and
# memory searches (-use_cmp=0 -use_memmem=0: those operands include addresses, which differ
# from run to run), and no timed re-reading of the corpus directory (-reload=0: it runs
# extra inputs at moments set by the clock). -max_total_time only cuts a slow machine's run
# short, to a prefix of the same sequence of inputs (docs/fuzzing.md).
fuzz_mutate() {
  local name=$1 runs=$2 corpus=build/sanitize/mutation/$1 artifacts=build/sanitize/artifacts/$1- log
  rm -rf "$corpus"
  mkdir -p "$corpus" build/sanitize/artifacts
  cp fuzz/corpus/"$name"/* "$corpus"/
  echo "==> fuzz_$name: seeded mutation run, $runs inputs"
  log=$(ELLIPSECT_FUZZ_SIMD_TARGET=EMU128 build/sanitize/fuzz/fuzz_"$name" -seed=1 -runs="$runs" -use_cmp=0 \
    -use_memmem=0 -reload=0 -max_total_time=180 -max_len=4096 -timeout=10 -artifact_prefix="$artifacts" "$corpus" 2>&1) ||
    { echo "$log" | tail -40; return 1; }
}

# Executions per target for the CI mutation run, the corpus's included: 15 to 30 s each on
# one core.
declare -A fuzz_runs=([factories]=250000 [queries]=3000 [intersect2]=150000 [niemitalo]=90000 [scene]=30000
                       [rigid]=8000 [broad_phase]=6000 [enclosing]=2000 [inscribed]=3000 [fit]=10000)

# Every target's check and mutation run, as many at once as there are cores; each target's
# output is printed when it ends, and the step fails if any target did (all of them run).
fuzz_all() {
  local name logs=build/sanitize/fuzz-logs failed=()
  rm -rf "$logs"
  mkdir -p "$logs"
  # The longest runs first (rigid, queries), so that the others fill the other cores.
  for name in rigid queries $(fuzz_targets | grep -vx 'rigid\|queries'); do
    while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do sleep 1; done
    {
      status=1
      fuzz_check "$name" && fuzz_mutate "$name" "${fuzz_runs[$name]}" && status=0
      echo "$status" >"$logs/$name.rc"
    } >"$logs/$name.log" 2>&1 &
  done
  wait
  for name in $(fuzz_targets); do
    cat "$logs/$name.log"
    [ "$(cat "$logs/$name.rc")" = 0 ] || failed+=("$name")
  done
  [ ${#failed[@]} -eq 0 ] || { echo "==> fuzz targets failed: ${failed[*]}" >&2; return 1; }
}

# ---- web: the demo page (web/) --------------------------------------------------------
# Debian's emscripten ships its system libraries prebuilt (a frozen cache), so nothing of
# Emscripten's own is compiled here. Its JS optimizer needs Debian's acorn module, which a
# Node from elsewhere does not look for: NODE_PATH. The 3D page's three.js comes from
# web/node_modules (npm ci), copied into the site by the build.
build_web() {
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
  NODE_PATH=/usr/share/nodejs emcmake cmake -S web -B build/web -G Ninja "${launcher[@]}" >/dev/null
  NODE_PATH=/usr/share/nodejs cmake --build build/web -j "$(nproc)"
  echo "==> demo page: build/web/site/ ($(stat -c %s build/web/site/ellipsect.wasm) bytes of wasm)"
}

# The browser test (web/tests/browser_test.mjs): headless Chromium drives every demo and
# compares the page with the native answers; screenshots and results in build/web/test-output.
web_test() {
  build_web
  cmake --build build/release --target web_native_answers
  node web/tests/browser_test.mjs build/web/site build/release/tests/web_native_answers build/web/test-output
}
# ---- end web

# The Python package: a virtual environment build/venv from Debian's python3 (with its
# packages), `pip install ./python` (the module built by the project's CMake in the Release
# tree, beside the library it links), then its pytest suite (docs/python.md).
python_test() {
  [ -x build/venv/bin/python ] || /usr/bin/python3 -m venv --system-site-packages build/venv
  # pip's CMake configures the Release tree again: its cache keeps the compiler launcher.
  ELLIPSECT_BUILD_DIR=build/release CMAKE_BUILD_PARALLEL_LEVEL=$(nproc) \
    build/venv/bin/pip install -q --no-build-isolation ./python
  build/venv/bin/python -m pytest -q python/tests
}

case "${1:-}" in
  example)
    # The C++ packages alone, and the program alone, in a tree of its own (build/example): the
    # library's double queries (the program's), its files compiled in batches.
    install_missing "${cxx_packages[@]}"
    step "build: the library and the ellipsect program"
    build build/example --target ellipsect_cli -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=OFF \
      -DELLIPSECT_BUILD_BENCH=OFF -DELLIPSECT_BUILD_TOOLS=ON -DELLIPSECT_DOUBLE_ONLY=ON -DELLIPSECT_UNITY_LIBRARY=ON
    step "ellipsect check examples/scenes/swept_2d.json"
    ./build/example/tools/ellipsect check examples/scenes/swept_2d.json
    ./build/example/tools/ellipsect render examples/scenes/swept_2d.json -o build/example/swept_2d.svg
    ./build/example/tools/ellipsect render examples/scenes/swept_2d.json -o build/example/swept_2d.png
    step "picture of the first contact: build/example/swept_2d.svg (and swept_2d.png)"
    ;;
  test)
    install_missing
    # Options set explicitly: `example` may have configured build/release without tests.
    step "Release build"
    # The benchmarks are built by `bench`, which runs them.
    build build/release -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=ON -DELLIPSECT_BUILD_BENCH=OFF \
      -DELLIPSECT_BUILD_TOOLS=ON
    # The sanitized build runs alongside the next three steps at the same priority, sharing the cores
    # (a test suite's last tests, the browser, pytest); in a process group of its own
    # (set -m), which ends with the script.
    step "sanitized build (tests and fuzz targets), in the background: build/sanitize.log"
    set -m
    build_sanitized all fuzz >build/sanitize.log 2>&1 &
    sanitized_build=$!
    set +m
    trap 'kill -- "-$sanitized_build" 2>/dev/null || true' EXIT
    step "Release tests"
    (cd build/release && ctest --output-on-failure --no-tests=error -j "$(nproc)")
    step "demo page: build and browser test"
    web_test
    step "Python package: build and tests"
    python_test
    step "sanitized build: waiting for it"
    wait "$sanitized_build" || { cat build/sanitize.log; exit 1; }
    trap - EXIT
    cat build/sanitize.log
    # Same suite under the sanitizers, fewer random cases per property test.
    step "sanitized tests"
    (cd build/sanitize && ELLIPSECT_CASE_SCALE=0.05 ctest --output-on-failure --no-tests=error -j "$(nproc)")
    step "fuzz targets: kept inputs, then corpus and seeded mutation run"
    fuzz_all
    # The certified fallbacks as platforms whose long double is double compute them
    # (src/detail/wide.hpp): the unit, property and reference suites in build/narrow.
    step "emulated wide type: build and tests"
    build build/narrow --target unit_tests --target property_tests --target reference_selftest \
      -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=ON -DELLIPSECT_BUILD_BENCH=OFF -DELLIPSECT_BUILD_TOOLS=OFF \
      -DELLIPSECT_EMULATED_WIDE=ON -DELLIPSECT_CUDA=OFF -DELLIPSECT_UNITY_LIBRARY=ON
    (cd build/narrow && ctest --output-on-failure --no-tests=error -j "$(nproc)" -E consumer_project)
    step "all passed"
    ;;
  fuzz)
    install_missing
    build_sanitized fuzz
    # fuzz [NAME [SECONDS]]: new inputs are added to fuzz/corpus/NAME; failures are written
    # as crash-* files in the current directory (docs/fuzzing.md: keep them as regressions).
    for name in ${2:-$(fuzz_targets)}; do
      [[ -f fuzz/${name}_fuzz.cpp ]] || { echo "no fuzz target $name (see fuzz/)" >&2; exit 2; }
      build/sanitize/fuzz/fuzz_"$name" -max_total_time="${3:-600}" -max_len=4096 -timeout=10 -jobs="$(nproc)" \
        -workers="$(nproc)" fuzz/corpus/"$name"
    done
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
  web)
    install_missing
    cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DELLIPSECT_BUILD_TESTS=ON \
      -DELLIPSECT_BUILD_BENCH=ON -DELLIPSECT_BUILD_TOOLS=ON >/dev/null
    web_test
    ;;
  demo)
    install_missing
    build_web
    echo "==> open http://127.0.0.1:${2:-8000}/ (Ctrl-C stops the server)"
    /usr/bin/python3 -m http.server "${2:-8000}" --bind 127.0.0.1 --directory build/web/site
    ;;
  *)
    echo "usage: bash scripts/run.sh example|test|web|demo [PORT]|bench [NAME [ARGS...]]|fuzz [NAME [SECONDS]]" >&2
    exit 2
    ;;
esac
