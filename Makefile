# SPDX-License-Identifier: MIT
# make demo | test | bench | sanitize-test — each installs what is missing, then builds.
# sanitize-test (ASan + UBSan, Debug) runs every test but those labelled `slow`, which take
# minutes there: gtest ones named by meshmorph_add_test(... SLOW filter) in tests/CMakeLists.txt,
# CLI ones labelled in tests/cli/CMakeLists.txt. `make test` runs them all.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps build demo test bench sanitize-test clean

all: build

deps:
	@scripts/install-deps

$(BUILD)/build.ninja: | deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null

build: deps $(BUILD)/build.ninja
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@scripts/demo $(BUILD)/bin/meshmorph

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@scripts/bench $(BUILD)

sanitize-test: deps
	@cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DMESHMORPH_SANITIZE=ON -DMESHMORPH_BUILD_BENCH=OFF -DMESHMORPH_BUILD_PYTHON=OFF >/dev/null
	@cmake --build build-sanitize -j $(JOBS)
	@cd build-sanitize && ctest --output-on-failure -j $(JOBS) -LE slow

clean:
	rm -rf $(BUILD) build-sanitize
