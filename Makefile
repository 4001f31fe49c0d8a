# Two-command quick start: `make demo` and `make test`. Both install the Debian packages first.
# Thin wrapper over the CMake presets in CMakePresets.json.
PRESET ?= ci
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)

.PHONY: all deps configure build demo test gallery goldens lean test-asan fuzz clean

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

# Every shipped scene at 1280x720 on one HTML page with its render settings and frame statistics.
gallery: build
	./scripts/make-gallery $(BUILD)/apps/player/sylva-player out/gallery

# Regenerates tests/golden/images after a deliberate change of the picture (tests/golden/README.md).
goldens: configure
	PRESET=$(PRESET) ./scripts/update-goldens

# No retries: a test that fails once has found a bug (in the code or in the test).
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 300

# Lean player: the `lean` preset (terrain + grass, no ImGui) builds sylva-player alone; then
# scripts/check-lean plays the default scene headless and checks it refuses built-out modules.
lean: deps
	cmake --preset lean >/dev/null
	cmake --build build/lean -j $(JOBS) --target sylva-player
	./scripts/check-lean build/lean/apps/player/sylva-player

# Sanitizer job: the `asan` preset (the `dev` preset's Debug, ASan + UBSan, with -g1 line tables:
# reports keep file:line, ~9 % less compile CPU) builds only the tests of the kinds in ASAN_KINDS
# (target sylva_tests_<kind>: those tests and what they link; a whole Debug + ASan tree does not
# fit CI's time) and runs those labels. Any report fails the test that made it.
ASAN_KINDS ?= unit
empty :=
space := $(empty) $(empty)
SANITIZER_ENV := ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1 \
                 LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan-suppressions.txt \
                 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
test-asan: deps
	cmake --preset asan >/dev/null
	$(SANITIZER_ENV) cmake --build build/asan -j $(JOBS) --target $(addprefix sylva_tests_,$(ASAN_KINDS))
	$(SANITIZER_ENV) ctest --test-dir build/asan --output-on-failure -j $(JOBS) --timeout 600 \
	  -L '^($(subst $(space),|,$(strip $(ASAN_KINDS))))$$'

# Fuzzing (fuzz/README.md): the `fuzz` preset (clang 14, libFuzzer + ASan/UBSan) builds the fuzz
# targets and only the libraries they link, then runs each for FUZZ_SECONDS (CI: 20), FUZZ_JOBS
# (default: nproc) at a time, and starts no more after the first crash, printing its reproducer.
# FUZZ_TARGETS="scene_json obj" runs only those.
# Corpora grow in build/fuzz-work, outside git.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?=
fuzz: deps
	cmake --preset fuzz >/dev/null
	nice -n 5 cmake --build build/fuzz -j $(JOBS) --target sylva-fuzz-all
	fuzz/run-fuzzers build/fuzz build/fuzz-work $(FUZZ_SECONDS) $(FUZZ_TARGETS)

clean:
	rm -rf build out
