# The README's two commands. Both install missing Debian packages first, then configure and
# build through a CMake preset (see CMakePresets.json).
PRESET ?= release
JOBS ?= $(shell nproc)
OUT ?= out

.PHONY: demo test deps configure build asan asan-gpu-free fuzz draw-cost clean

deps:
	./scripts/install-deps.sh

configure: deps
	cmake --preset $(PRESET)

build: configure
	cmake --build --preset $(PRESET) -j $(JOBS)

# Renders the flagship sample headless and writes its pictures under $(OUT)/.
demo: build
	./scripts/demo.sh build/$(PRESET) $(OUT)

# Runs every test (unit, render on GL and Vulkan, cross-backend).
test: build
	ctest --preset $(PRESET) -j $(JOBS)

# The same tests under AddressSanitizer + UndefinedBehaviorSanitizer.
asan:
	$(MAKE) test PRESET=asan

# The GPU-free tests (frame graph, graph JSON, glTF import, rhi utilities) under ASan + UBSan,
# building only what they need; .ci/run runs it after `make test`.
asan-gpu-free:
	$(MAKE) test PRESET=asan-gpu-free

# Builds the libFuzzer harnesses with clang 14 (installed by install-deps.sh --fuzz) into
# build/fuzz/fuzz/; docs/fuzzing.md says how to run them.
fuzz:
	./scripts/install-deps.sh --fuzz
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)

# Instructions and heap allocations per draw, loom's RHI against raw GL and raw Vulkan doing the
# same work, counted by callgrind (installed by install-deps.sh --bench); prints the table of
# docs/BENCHMARKS.md, "The RHI per draw".
draw-cost: build
	./scripts/install-deps.sh --bench
	python3 tests/bench/draw_cost/draw_cost.py build/$(PRESET)

clean:
	rm -rf build $(OUT)
