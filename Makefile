# Thin wrapper around CMake, ctest and bats.  Every target that needs the
# toolchain runs scripts/install-deps.sh first (a fast no-op when all the
# Debian packages are present), so `make demo` and `make test` work as root
# on a fresh Debian 12 machine.
.PHONY: all deps build test unit-test shell-test python-test asan-test demo bench fuzz install clean

BUILD_DIR    ?= build
ASAN_DIR     ?= build-asan
BUILD_TYPE   ?= Release
JOBS         ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX       ?= /usr/local
FUZZ_SECONDS ?= 60
# Debian's Python, which has python3-numpy and python3-pybind11 (another
# python3 may come first on PATH); the rscene package is built for it.
PYTHON       ?= /usr/bin/python3

all: build

deps:
	sh scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DRSCENE_REQUIRE_RENDER=ON \
	  -DPython3_EXECUTABLE=$(PYTHON)
	cmake --build $(BUILD_DIR) -j$(JOBS)

# Unit tests, end-to-end shell tests, the Python package's tests, then the unit tests again under
# AddressSanitizer and UndefinedBehaviorSanitizer.
test: build
	$(MAKE) --no-print-directory unit-test shell-test python-test asan-test

unit-test:
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j$(JOBS)

shell-test:
	RSCENE_BIN="$(CURDIR)/$(BUILD_DIR)/bin" bats shell-tests

# The `rscene` Python package (python/tests, pytest) against the build tree;
# skipped with a message when the build has RSCENE_BUILD_PYTHON off.
python-test:
	@if grep -q '^RSCENE_BUILD_PYTHON:BOOL=ON' $(BUILD_DIR)/CMakeCache.txt 2>/dev/null; then \
	  PYTHONPATH="$(abspath $(BUILD_DIR))/python" RSCENE_BIN="$(abspath $(BUILD_DIR))/bin" \
	    $(PYTHON) -m pytest -q -p no:cacheprovider python/tests; \
	else echo "python-test: skipped, $(BUILD_DIR) was configured with RSCENE_BUILD_PYTHON off"; fi

# Only core_tests, scene_tests (the typed scene model) and asset_tests (the
# image decoders meet hostile input) are built here; ctest lists the other
# test executables as <target>_NOT_BUILT, which are left out.
asan-test:
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DRSCENE_SANITIZE=ON -DRSCENE_BUILD_TOOLS=OFF -DRSCENE_BUILD_PYTHON=OFF
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
