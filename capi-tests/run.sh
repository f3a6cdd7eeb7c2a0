#!/usr/bin/env bash
# Builds libdnsr, then builds and runs the C API tests (and the minimal C example) with AddressSanitizer and the
# Vulkan validation layer. Usage: bash capi-tests/run.sh   (DNSR_DEVICE=<name substring> picks a device;
# lavapipe by default, like `make test`).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

export DNSR_DEVICE="${DNSR_DEVICE:-llvmpipe}"
unset VK_LOADER_DEBUG
build=build/capi-tests

cargo build --release --lib
cmake -S capi-tests -B "$build" -DCMAKE_BUILD_TYPE=Release -DDNSR_ASAN=ON -DDNSR_LIB="$PWD/target/release/libdnsr.so"
cmake --build "$build" -j "$(nproc)"

# Leak detection stays on: CTest passes ASAN_OPTIONS/LSAN_OPTIONS (with capi-tests/lsan.supp) to every test.
status=0
# Side by side: each test keeps one core busy (CMakeLists.txt; the fuzz's seeds and halves are tests of their own).
(cd "$build" && ctest --output-on-failure -j "$(nproc)") | tee "$build/ctest.out" || status=$?

summary=$(grep -E '^[0-9]+% tests passed' "$build/ctest.out" || echo "no CTest summary")
cases=$(grep -ohE 'bad_input: [0-9]+ cases run' "$build/Testing/Temporary/LastTest.log" | grep -oE '[0-9]+' || echo "?")
fuzz=$(grep -ohE 'fuzz: [0-9]+ calls, [0-9]+ succeeded, [0-9]+ refused' "$build/Testing/Temporary/LastTest.log" | paste -sd';' -)
echo "capi-tests: ${summary}; bad_input: ${cases} misuse cases run; ${fuzz:-fuzz: ?}; device: ${DNSR_DEVICE}"
exit "$status"
