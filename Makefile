# The two commands of the README, plus the pieces they are made of.
#   make demo   install missing Debian packages, build, run the main job
#   make test   same set-up, then the whole test suite through CTest
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
HEXCAL = $(BUILD_DIR)/app/hexcal

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

build: configure
	cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	$(HEXCAL) demo

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j$(JOBS)

bench: build
	$(BUILD_DIR)/bench/hexcal_bench_kinematics

clean:
	rm -rf $(BUILD_DIR)
