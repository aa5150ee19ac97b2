# The README's two commands. Both install missing Debian packages first, then configure and
# build through a CMake preset (see CMakePresets.json).
PRESET ?= release
JOBS ?= $(shell nproc)
OUT ?= out

.PHONY: demo test deps configure build asan clean

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

clean:
	rm -rf build $(OUT)
