# The two README commands. Each installs what is missing first.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps build test test-cluster demo bench fuzz asan clean format lint

all: build

deps:
	@bash scripts/install-deps.sh --cluster
	@bash tests/mcp_client/install.sh
	@bash tests/review_browser/install.sh

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

# The tests, then (scripts/sanitize.sh) the input-parsing modules' tests and
# the bad-input suite under ASan + UBSan, and each fuzz harness for
# FUZZ_SECONDS (default 10).
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	JOBS=$(JOBS) FUZZ_SECONDS=$(or $(FUZZ_SECONDS),10) bash scripts/sanitize.sh

# The tests that need Slurm (tests/cluster/run.sh; also ctest cluster/slurm in
# `make test`) on a one-node cluster on localhost (scripts/slurm/local-cluster.sh;
# root), brought up for them and down after unless it was already up.
test-cluster: build
	bash tests/cluster/on-local-cluster.sh $(BUILD)

# Formats every C++ file by .clang-format (ctest style/clang_format checks it).
format:
	find src bench fuzz -name '*.cc' -o -name '*.h' | xargs clang-format -i

# The linter (.clang-tidy) over the library's sources, with the build's
# compile commands; for developers (slow: minutes per module on 2 cores).
lint: build
	find src -name '*.cc' ! -name '*_test.cc' | xargs -P $(JOBS) -n 4 clang-tidy -p $(BUILD) --quiet

demo: build
	$(BUILD)/asbuilt demo

bench: build
	bash scripts/install-deps.sh --bench
	cmake --build $(BUILD) -j $(JOBS) --target benchmarks
	bash bench/run.sh $(BUILD)

# Each libFuzzer harness for FUZZ_SECONDS (default 20; nightly: make fuzz FUZZ_SECONDS=3600).
fuzz: deps
	bash scripts/fuzz.sh $(or $(FUZZ_SECONDS),20)

# The library and tests built with AddressSanitizer + UBSan (without the
# LibTorch segmenter: Debian's prebuilt LibTorch is not instrumented).
asan: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DASBUILT_SANITIZE=ON \
	  -DASBUILT_WITH_TORCH=OFF -DASBUILT_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=0 ctest --test-dir build-asan --output-on-failure -j $(JOBS) -E 'seg/|sdk_client'

clean:
	rm -rf $(BUILD)
