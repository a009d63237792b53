# The two commands of the README, plus the pieces they are made of.
#   make demo   install missing Debian packages, build, run the main job
#   make test   same set-up, then the whole test suite through CTest
#   make sanitize  the unit tests again under ASan + UBSan, in build-asan (docs/hardening.md)
#   make fuzz   the libFuzzer targets, a short run of each, in build-fuzz (docs/hardening.md)
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
HEXCAL = $(BUILD_DIR)/app/hexcal

.PHONY: all deps configure build demo test sanitize bench clean

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

build: configure
	cmake --build $(BUILD_DIR) -j$(JOBS)

# The whole flow on a virtual robot and camera; the session is left in build/demo.
demo: build
	$(HEXCAL) demo --out $(BUILD_DIR)/demo --force

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j$(JOBS)

# Unit tests only (core/, vision/, charts/, devices/, session/, sim/, report/, workflow/ in CTest; the cli/ cases are left out to
# keep CI short, and so is building the CLI: target hexcal_unit_tests). Any sanitizer report
# fails the test.
ASAN_BUILD_DIR ?= build-asan
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# -O1 -g1 (line tables: file and line in every report): half the compile time
# of RelWithDebInfo's -O2 -g, the tests about 5-10 % slower (docs/hardening.md).
SANITIZER_FLAGS = "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
sanitize: deps
	cmake -S . -B $(ASAN_BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo $(SANITIZER_FLAGS) -DHEXCAL_SANITIZE=ON \
	  -DHEXCAL_BUILD_BENCHMARKS=OFF -DHEXCAL_BUILD_GUI=OFF
	cmake --build $(ASAN_BUILD_DIR) -j$(JOBS) --target hexcal_unit_tests
	$(SANITIZER_ENV) scripts/sanitize-ctest.sh $(ASAN_BUILD_DIR) $(JOBS)

# The libFuzzer targets of fuzz/ (clang, ASan + UBSan) and a bounded run of each
# from its seed corpus through CTest; any crash, leak or UB report fails.
# Long runs: docs/hardening.md.
FUZZ_BUILD_DIR ?= build-fuzz
.PHONY: fuzz
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo $(SANITIZER_FLAGS) \
	  -DHEXCAL_FUZZ=ON \
	  -DHEXCAL_BUILD_BENCHMARKS=OFF
	cmake --build $(FUZZ_BUILD_DIR) -j$(JOBS) --target hexcal_fuzzers
	ctest --test-dir $(FUZZ_BUILD_DIR) -R '^fuzz/' --output-on-failure -j$(JOBS)

bench: build
	$(BUILD_DIR)/bench/hexcal_bench_kinematics

clean:
	rm -rf $(BUILD_DIR)
