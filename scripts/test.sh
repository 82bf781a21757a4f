#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (unit, render and GUI tests) through
# CTest under Xvfb. Then the no-app stage (FFDKIT_NOAPP_STAGE=0 skips it): the libraries, the CLI
# and the Python module built without Qt (-DFFDKIT_BUILD_APP=OFF, build-noapp/; and without VTK
# too, build-novtk/) and their tests, install and consumer tests run. Then the sanitizer stage
# (FFDKIT_SANITIZE_STAGE=0 skips it): the core libraries and the CLI built again with ASan +
# UBSan at -O0 and -O1 (build-sanitize/, no Qt window, no Python module, no benchmarks) and every `core`
# test run under them: unit, CLI and file tests, and every fuzz target over its corpus and saved
# crash inputs. And the app's sanitizer stage (FFDKIT_SANITIZE_APP_STAGE=0 skips it): the window
# built with ASan + UBSan (build-sanitize-app/) and the monkey test's random GUI actions run under
# them, beside the sanitizer stage's tests. Prints CTest's summaries; exits non-zero on any
# failure or sanitizer report.
#   scripts/test.sh [extra ctest arguments, e.g. -L core]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup-deps.sh"
"$root/scripts/build.sh"
build="${FFDKIT_BUILD_DIR:-$root/build}"
jobs="${FFDKIT_JOBS:-$(nproc)}"
# Tests at once: one more than the cores (FFDKIT_TEST_JOBS). Many tests spend part of their time
# waiting (a window's timers, a child process, mpirun's start-up, Xvfb), and with one test per
# core a core stood idle for about a sixth of the main build's test run (/usr/bin/time of its ctest:
# 439 s of CPU in 266 s on 2 cores); a third test fills those gaps.
test_jobs="${FFDKIT_TEST_JOBS:-$((jobs + 1))}"

# GUI and render tests need a display: run the whole suite inside one Xvfb server (Mesa's
# software GL). XDG_RUNTIME_DIR keeps Qt from warning on every start. -noreset: an X server
# resets when its last client leaves, and a connection opened during the reset fails; render
# tests without a Qt window (QTEST_GUILESS_MAIN) open and close VTK windows one after another,
# and on a loaded machine the next one landed in the reset: VTK aborts on "bad X server
# connection" (display_modes_test failed every run on a busy machine; with -noreset none did).
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
export QT_QPA_PLATFORM=xcb
# OpenMP threads that spin while idle would starve the other tests running beside them.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --test-dir "$build" --output-on-failure --parallel "$test_jobs" --timeout 600 "$@"

# What the whole command and each stage cost from a fresh clone: docs/architecture.md, "Building
# and testing"; each stage below prints its own times.

# The library without the window (FFDKIT_NOAPP_STAGE=0 skips it): configured with
# -DFFDKIT_BUILD_APP=OFF in build-noapp/ (no Qt looked for or linked; no benchmarks), built (the
# compiler cache serves what the main build compiled) and the tests the configuration changes
# run: the CLI's, the Python module's, and the install tree, the per-component consumer projects
# and the Debian package as a user without Qt gets them. Then the same without VTK in
# build-novtk/, every test it registers.
if [ "${FFDKIT_NOAPP_STAGE:-1}" = "1" ]; then
  noapp="${FFDKIT_NOAPP_BUILD_DIR:-$root/build-noapp}"
  stage_start=$(date +%s)
  FFDKIT_BUILD_DIR="$noapp" "$root/scripts/build.sh" -DFFDKIT_BUILD_APP=OFF -DFFDKIT_BUILD_BENCH=OFF
  if grep -q "^Qt6_DIR:" "$noapp/CMakeCache.txt"; then
    echo "no-app stage: the configuration without the window looked for Qt ($noapp/CMakeCache.txt)" >&2
    exit 1
  fi
  built=$(date +%s)
  # The libraries compile from the same sources with the same flags as in the main build, whose
  # stage ran their unit tests: here run what the configuration changes (the CLI, the Python
  # module, the install tree, the consumer projects and the Debian package, the docs' snippets).
  # FFDKIT_NOAPP_ALL_TESTS=1 runs every test it registers.
  noapp_tests=(-R "install_|deb_|^[Cc]li|python|Docs\\.")
  if [ "${FFDKIT_NOAPP_ALL_TESTS:-0}" = "1" ]; then noapp_tests=(); fi
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
    ctest --test-dir "$noapp" --output-on-failure --parallel "$test_jobs" --timeout 600 "${noapp_tests[@]}" "$@"
  tested=$(date +%s)
  # The same without VTK and OpenCASCADE (-DFFDKIT_WITH_VTK=OFF -DFFDKIT_WITH_CAD=OFF, build-novtk/):
  # neither is looked for, ffdkit-cli refuses STEP and IGES inputs, meshio
  # refuses to write .vtp and legacy .vtk, ffdkit-cli has no render or plot; the tests that need
  # no VTK run, with the install and consumer tests (nothing may link or look for VTK).
  novtk="${FFDKIT_NOVTK_BUILD_DIR:-$root/build-novtk}"
  FFDKIT_BUILD_DIR="$novtk" "$root/scripts/build.sh" -DFFDKIT_BUILD_APP=OFF -DFFDKIT_WITH_VTK=OFF \
    -DFFDKIT_BUILD_BENCH=OFF -DFFDKIT_WITH_CAD=OFF
  if grep -q "^Qt6_DIR:\|^VTK_DIR:" "$novtk/CMakeCache.txt"; then
    echo "no-app stage: the configuration without VTK looked for Qt or VTK ($novtk/CMakeCache.txt)" >&2
    exit 1
  fi
  ctest --test-dir "$novtk" --output-on-failure --parallel "$test_jobs" --timeout 600 "$@"
  echo "no-app stage: with VTK build $((built - stage_start)) s, tests $((tested - built)) s;" \
       "without VTK build and tests $(($(date +%s) - tested)) s"
fi

# The sanitizer stages' compiler (the main build above stays GCC's at -O3): clang. Under ASan +
# UBSan at -O1 GCC 12 compiles about three times slower than clang 14 (ffd/src/embedding.cpp:
# 57 s of CPU against 16 s), and these stages compile every core library, test and fuzz target
# again: cost in docs/robustness.md. FFDKIT_SANITIZE_COMPILER=gcc builds them with GCC.
sanitize_compiler="${FFDKIT_SANITIZE_COMPILER:-clang}"
case "$sanitize_compiler" in
  clang) sanitize_cc=clang sanitize_cxx=clang++ ;;
  gcc) sanitize_cc=gcc sanitize_cxx=g++ ;;
  *) echo "test.sh: FFDKIT_SANITIZE_COMPILER is clang or gcc, not '$sanitize_compiler'" >&2; exit 2 ;;
esac
# sanitizer_build DIR [build.sh arguments]: builds DIR with that compiler. CMake cannot change a
# build folder's compiler in place: a folder configured with another one (an older checkout's
# GCC build-sanitize/) is configured again from scratch.
sanitizer_build() {
  local dir="$1"; shift
  local cc cxx
  if ! cc=$(command -v "$sanitize_cc") || ! cxx=$(command -v "$sanitize_cxx"); then
    echo "test.sh: the sanitizer stages build with $sanitize_cxx, which is not installed:" \
         "scripts/setup-deps.sh installs it (clang, libomp-14-dev, libclang-rt-14-dev)," \
         "or FFDKIT_SANITIZE_COMPILER=gcc builds them with GCC (slower)" >&2
    exit 1
  fi
  local configured=""
  if [ -f "$dir/CMakeCache.txt" ]; then
    configured=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$dir/CMakeCache.txt")
  fi
  if [ -n "$configured" ] && [ "$configured" != "$cxx" ]; then
    echo "test.sh: $dir was configured with $configured; configuring it again with $cxx"
    rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
  fi
  FFDKIT_BUILD_DIR="$dir" "$root/scripts/build.sh" "$@" -DFFDKIT_SANITIZE=ON -DFFDKIT_BUILD_BENCH=OFF \
    "-DCMAKE_C_COMPILER=$cc" "-DCMAKE_CXX_COMPILER=$cxx" "-DCMAKE_CXX_FLAGS_RELEASE=-O0 -DNDEBUG"
}

# The sanitizer stage (FFDKIT_SANITIZE_STAGE=0 skips it) and the window's sanitizer stage
# (FFDKIT_SANITIZE_APP_STAGE=0 skips it) are built one after the other (the second takes the core
# libraries from the compiler cache the first filled), then their tests run side by side: the
# monkey test is one process that keeps about one core busy, and beside CTest's tests it fills
# what the cores would leave idle. Its output is kept in build-sanitize-app/monkey.log and printed
# once it ends.
sanitize="${FFDKIT_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
sanitize_app="${FFDKIT_SANITIZE_APP_BUILD_DIR:-$root/build-sanitize-app}"
run_sanitize="${FFDKIT_SANITIZE_STAGE:-1}"
run_sanitize_app="${FFDKIT_SANITIZE_APP_STAGE:-1}"
# halt_on_error: the first report fails the test. Leaks are not checked: Qt, VTK, Mesa and tinygltf
# keep process-lifetime singletons that LeakSanitizer would report. (The fuzz corpus tests set
# their own options, see tests/fuzz/CMakeLists.txt.)
sanitizer_env=(env "ASAN_OPTIONS=halt_on_error=1:detect_leaks=0" "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")

if [ "$run_sanitize" = "1" ]; then
  stage_start=$(date +%s)
  # -O0, and -O1 for the targets whose tests compute through Eigen (cmake/FfdkitOptions.cmake):
  # the sanitizers check the same at either level, and -O0 compiles in less than half the time.
  sanitizer_build "$sanitize" -DFFDKIT_BUILD_APP=OFF
  echo "sanitizer stage: build $(($(date +%s) - stage_start)) s"
fi

# The window under the sanitizers: the app's libraries and the monkey test built with ASan +
# UBSan at -O0 (the core libraries as in the sanitizer stage) in build-sanitize-app/, then
# FFDKIT_SANITIZE_MONKEY_ACTIONS (default 1000) seeded random GUI actions with real events under
# Xvfb (tests/app/monkey_gui_test.cpp); any ASan error or UBSan report fails. Cost:
# docs/robustness.md.
monkey_pid=""
if [ "$run_sanitize_app" = "1" ]; then
  stage_start=$(date +%s)
  sanitizer_build "$sanitize_app" --target monkey_gui_test -DFFDKIT_BUILD_PYTHON=OFF
  echo "sanitizer app stage: build $(($(date +%s) - stage_start)) s"
  # The binary itself, not through CTest: its 300 s test timeout is the release build's.
  "${sanitizer_env[@]}" FFDKIT_MONKEY_ACTIONS="${FFDKIT_SANITIZE_MONKEY_ACTIONS:-1000}" \
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$sanitize_app/tests/app/monkey_gui_test" \
    > "$sanitize_app/monkey.log" 2>&1 &
  monkey_pid=$!
  # A failure or an interrupt before it ends does not leave it running.
  trap 'kill "$monkey_pid" 2>/dev/null || true' EXIT
fi

ctest_status=0
if [ "$run_sanitize" = "1" ]; then
  tests_start=$(date +%s)
  "${sanitizer_env[@]}" \
    ctest --test-dir "$sanitize" --output-on-failure --parallel "$test_jobs" --timeout 900 -L core \
    || ctest_status=$?
  echo "sanitizer stage: tests $(($(date +%s) - tests_start)) s"
fi

monkey_status=0
if [ -n "$monkey_pid" ]; then
  wait "$monkey_pid" || monkey_status=$?
  trap - EXIT
  cat "$sanitize_app/monkey.log"
  # Its own time is in its summary line above; waited for here, it ends no earlier than CTest.
  echo "sanitizer app stage: monkey test exit status $monkey_status"
fi
if [ "$ctest_status" != 0 ]; then
  echo "test.sh: the sanitizer stage's tests failed (CTest's summary above)" >&2
fi
if [ "$monkey_status" != 0 ]; then
  echo "test.sh: the monkey test under the sanitizers failed ($sanitize_app/monkey.log, printed above)" >&2
fi
if [ "$ctest_status" != 0 ] || [ "$monkey_status" != 0 ]; then
  exit 1
fi
