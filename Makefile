# Thin wrapper around CMake, ctest and bats.  Every target that needs the
# toolchain runs scripts/install-deps.sh first (a fast no-op when all the
# Debian packages are present), so `make demo` and `make test` work as root
# on a fresh Debian 12 machine.
.PHONY: all deps build test unit-test shell-test asan-test demo bench fuzz install clean

BUILD_DIR    ?= build
ASAN_DIR     ?= build-asan
BUILD_TYPE   ?= Release
JOBS         ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX       ?= /usr/local
FUZZ_SECONDS ?= 60

all: build

deps:
	sh scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DRSCENE_REQUIRE_RENDER=ON
	cmake --build $(BUILD_DIR) -j$(JOBS)

# Unit tests, end-to-end shell tests, then the unit tests again under
# AddressSanitizer and UndefinedBehaviorSanitizer.
test: build
	$(MAKE) --no-print-directory unit-test shell-test asan-test

unit-test:
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j$(JOBS)

shell-test:
	RSCENE_BIN="$(CURDIR)/$(BUILD_DIR)/bin" bats shell-tests

# Only core_tests, scene_tests (the typed scene model) and asset_tests (the
# image decoders meet hostile input) are built here; ctest lists the other
# test executables as <target>_NOT_BUILT, which are left out.
asan-test:
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DRSCENE_SANITIZE=ON -DRSCENE_BUILD_TOOLS=OFF
	cmake --build $(ASAN_DIR) -j$(JOBS) --target core_tests scene_tests asset_tests
	ctest --test-dir $(ASAN_DIR) --output-on-failure -j$(JOBS) -E '_NOT_BUILT$$'

demo: build
	sh scripts/demo.sh

bench: build
	bash bench/run.sh $(BUILD_DIR)/bin

fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) bash tests/fuzz/run.sh

install:
	cmake --install $(BUILD_DIR) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) out
