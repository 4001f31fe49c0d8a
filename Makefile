# Two-command quick start: `make demo` and `make test`. Both install the Debian packages first.
# Thin wrapper over the CMake presets in CMakePresets.json.
PRESET ?= ci
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)

.PHONY: all deps configure build demo test clean

all: build

deps:
	./scripts/install-deps

configure: deps
	cmake --preset $(PRESET) >/dev/null

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Plays the default scene: a window when a display exists, otherwise a headless render to a PNG.
demo: build
	@mkdir -p out
	$(BUILD)/apps/player/sylva-player --screenshot out/demo.png

# A test that fails is run once more before it counts as failed: GL timing tests on a loaded
# software rasteriser can miss a frame budget; a real failure fails twice.
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 300 --repeat until-pass:2

clean:
	rm -rf build out
