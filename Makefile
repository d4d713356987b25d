# SPDX-License-Identifier: MIT
# make demo | test | bench | sanitize-test | fuzz — each installs what is missing, then builds.
# sanitize-test (ASan + UBSan, Debug) runs every test but those labelled `slow`, which take
# minutes there: gtest ones named by meshmorph_add_test(... SLOW filter) in tests/CMakeLists.txt,
# CLI ones labelled in tests/cli/CMakeLists.txt. `make test` runs them all.
# fuzz builds the libFuzzer targets of tests/fuzz with clang, ASan and UBSan in build-fuzz (only
# the libraries they link) and runs each for FUZZ_SECONDS, or until FUZZ_RUNS executions (0 and
# -1: no limit), in FUZZ_JOBS processes (tests/fuzz/run_fuzz.sh); it fails on any crash.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= -1
FUZZ_JOBS ?= 1
FUZZ_TARGETS ?= msh vtu medit su2 case_file

.PHONY: all deps build demo test bench sanitize-test fuzz clean

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

fuzz: deps
	@cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Fuzz \
	  "-DCMAKE_CXX_FLAGS_FUZZ=-O2 -gline-tables-only" -DMESHMORPH_FUZZ=ON -DMESHMORPH_BUILD_TESTS=OFF \
	  -DMESHMORPH_BUILD_BENCH=OFF -DMESHMORPH_BUILD_PYTHON=OFF >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@tests/fuzz/run_fuzz.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_RUNS) $(FUZZ_JOBS) $(FUZZ_TARGETS)

clean:
	rm -rf $(BUILD) build-sanitize build-fuzz
