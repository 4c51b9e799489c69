# Two commands on a fresh Debian 12 machine: `make demo` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=

.PHONY: all deps build demo test test-fast bench asan-build asan tsan fuzz clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	./$(BUILD)/uavplan plan scenarios/demo.yaml -o out --export qgc,wpl,geojson,kml,csv
	./$(BUILD)/uavplan verify scenarios/demo.yaml out/plan.json
	./$(BUILD)/uavplan report scenarios/demo.yaml out/plan.json -o out/report.html

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The tests labelled fast (unit tests but the random-world sweeps, the quick CLI checks): a
# developer's loop, about a minute on two cores.
test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L fast

bench: build
	./$(BUILD)/bench/world_queries

# Sanitizer builds at -O1 with line tables only (-g1: enough for the sanitizers' stack traces, a
# fraction of full debug information to compile and link), no benchmark programs (the tests run
# the benchmark tables through `uavplan bench`).
SAN_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DUAVPLAN_BENCH_PROGRAMS=OFF
# One clang build with AddressSanitizer + UBSan serves the whole test suite and the libFuzzer
# targets (every object carries the fuzzer's coverage counters): one build, not two.
ASAN_BUILD = build-asan
asan-build: deps
	@cmake -S . -B $(ASAN_BUILD) $(SAN_FLAGS) -DUAVPLAN_SANITIZE=ON -DUAVPLAN_FUZZ=ON \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS)

# The whole test suite (unit, CLI, exports, the report's writer) under AddressSanitizer + UBSan
# (CI runs it); the random-world property sweeps run a sample of their worlds (core/build_info.h).
# Not under ASan: --threads giving the same bytes (release checks it; the threads' races are
# TSan's, below), and the export matrix (every bundled scenario planned and exported six times:
# the firmware rules are the release run's; the export code runs under ASan in the unit tests
# and the demo's read-back), and the MovingAI samples on the large maps (maze512-32-9, Complex:
# 100 s under ASan; the searches run under ASan in their unit tests and on the small maps), and
# the report in headless Chromium (it runs alone, the other core idle: 50 s; `uavplan report` runs
# under ASan in the CLI test, the browser's side is the same in release), and the SITL flights but
# the demo's (the simulators' wall time, not ours: `fly` runs under ASan on the demo's flight).
ASAN_SKIP ?= cli.threads_same_bytes|exports.matrix|movingai.maze512|movingai.Complex|report.browser|sitl.movers_fly|sitl.group9_fly|sitl.p5_small_fly|sitl.swap_fly|sitl.formation_fly
asan: asan-build
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS) -E "$(ASAN_SKIP)"

# The tests that run several threads (the rendezvous engines, directional A*'s engines, the
# cellular colony), under ThreadSanitizer (CI runs it). Not `batch`: Debian's oneTBB is not
# instrumented, so TSan cannot see the synchronisation of its task handoffs and would report
# every run's data.
TSAN_TESTS ?= Rendezvous|DirectionalAStar|Cellular|Cells|RoutesOnManyThreads
# Only the executables those tests are in. The libraries without precompiled headers and file by
# file (no unity batches): the layers up to evaluation are built as a user's compiler sees them,
# so a file that does not include what it uses fails here. Their unit tests are batched on
# precompiled headers (UAVPLAN_BATCH_TESTS): a test file is not what a user's program compiles.
TSAN_TARGETS ?= uavplan_coordination_test uavplan_evaluation_test uavplan_evaluation_property_test uavplan_planning_test
tsan: deps
	@cmake -S . -B build-tsan $(SAN_FLAGS) -DUAVPLAN_TSAN=ON -DUAVPLAN_PCH=OFF -DUAVPLAN_UNITY=OFF \
	  -DUAVPLAN_BATCH_TESTS=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target $(TSAN_TARGETS)
	cd build-tsan && TSAN_OPTIONS=halt_on_error=1 ctest --output-on-failure -j $(JOBS) -R "$(TSAN_TESTS)"

# libFuzzer on every reader of outside input, FUZZ_SECONDS each (CI: 60 s each), from the
# sanitizer build above.
FUZZ_SECONDS ?= 60
fuzz: asan-build
	bash fuzz/run.sh $(ASAN_BUILD) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD) build-asan build-tsan build-fuzz out
