#!/bin/sh
# The sanitizer build (ctest label `sanitize`, opt-in): configures a separate build tree with
# AddressSanitizer and UndefinedBehaviorSanitizer, builds it and runs its tests there.
#   usage: run.sh SOURCE_DIR BUILD_DIR
# PCRF_SANITIZE_JOBS (default 2) sets the build's and the tests' parallelism. Any sanitizer
# report fails the test that provoked it (halt_on_error, a non-zero exit), and so this one.
# Left out: the valgrind leak check (label `leak`: valgrind and ASan exclude each other) and
# the Python module (an ASan shared object needs the runtime preloaded into python3).
set -eu
source_dir=$1
tree=$2
jobs=${PCRF_SANITIZE_JOBS:-2}
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
# GCC 12 warns falsely under the sanitizers' instrumentation (std::regex's std::function in
# libstdc++, which tests use: "may be used uninitialized"); the project builds with -Werror,
# so the tests of this tree build without that warning (PCRF_TEST_CXX_FLAGS).
test_flags="-Wno-maybe-uninitialized"
launcher=""
if command -v ccache >/dev/null 2>&1; then
  launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache"
fi
# -O1: sanitizers want little inlining for readable stacks, and it builds faster than -O2.
# shellcheck disable=SC2086
cmake -S "$source_dir" -B "$tree" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DPCRF_BUILD_BENCH=OFF -DPCRF_SANITIZE_TEST=OFF -DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON \
  -DPCRF_TEST_TIMEOUT_S=1800 -DPCRF_TEST_CXX_FLAGS="$test_flags" $launcher
cmake --build "$tree" -j "$jobs"
# LeakSanitizer is off: every `pcrf study` (Open MPI's plugins, unloaded by exit, and the
# libcrypto they load) reports leaks that no suppression by library name can match. The
# valgrind check of label `leak` covers the engine's own objects in the normal build.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=0:strict_string_checks=1:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir "$tree" -j "$jobs" --output-on-failure -LE "leak|python|sanitize"
