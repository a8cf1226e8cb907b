# The two commands a new user types (see README.md): `make demo` and `make test`.
# Both install the dependencies from Debian's packages if missing and build in
# Release into build/.
BUILD ?= build
JOBS ?= $(shell nproc)
# Extra CMake options for the build/ configuration (.ci/run sets some).
CMAKE_ARGS ?=

.PHONY: all deps configure build demo test sanitize fuzz bench clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DPENUMBRA_BUILD_TESTS=ON $(CMAKE_ARGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@$(BUILD)/penumbra render --demo -o $(BUILD)/demo.png

test: build
	@scripts/install-deps.sh --web-tests
	@ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The unit test suites under ASan and UBSan in build-sanitize/ (CI runs it
# after `test`); docs/RELIABILITY.md.
sanitize: deps
	@scripts/sanitize.sh

# Every fuzz target for FUZZ_SECONDS each (clang, build-fuzz/); docs/RELIABILITY.md.
FUZZ_SECONDS ?= 600
fuzz:
	@scripts/fuzz.sh $(FUZZ_SECONDS)

bench: configure
	@cmake -S . -B $(BUILD) -DPENUMBRA_BUILD_BENCHMARKS=ON > /dev/null
	@cmake --build $(BUILD) -j $(JOBS)

clean:
	rm -rf $(BUILD)
