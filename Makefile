# gikiosk — one entry point (DESIGN §1). `make` builds build/gikiosk.
# Targets: all run test bench calibrate references scenes deps install asan tsan fuzz clean

PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build
CC      ?= cc
CXX     ?= c++

# Debian packages (DESIGN §2); `make deps` installs the missing ones.
DEB_PACKAGES := build-essential pkg-config libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri \
	libdrm-dev libgbm-dev libgpiod-dev libtinygltf-dev libopenimageio-dev openimageio-tools \
	libinih-dev libcmocka-dev glslang-tools gnuplot-nox fonts-dejavu-core libstb-dev \
	clang libclang-rt-14-dev jq python3 systemd libdraco-dev nlohmann-json3-dev \
	libmeshoptimizer-dev

PKGS := egl glesv2 gbm libdrm libgpiod tinygltf OpenImageIO inih stb draco
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
# libmeshoptimizer ships no pkg-config file
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lmeshoptimizer

# libgpiod v1 (Debian 12) or v2 (backports, Debian 13), chosen by the library's version.
GPIOD_MAJOR = $(firstword $(subst ., ,$(shell pkg-config --modversion libgpiod 2>/dev/null)))

WERROR   := $(if $(CI),-Werror,)
OPT      ?= -O2
COMMON   := $(OPT) -g -Wall -Wextra $(WERROR) -Iapp -I. -D_GNU_SOURCE -DGK_GPIOD_MAJOR=$(or $(GPIOD_MAJOR),1) \
	-DGK_VERSION=\"$(shell cat VERSION 2>/dev/null || echo 0.1.0)\"
CFLAGS_ALL   = -std=c11 $(COMMON) $(PKG_CFLAGS) $(SANITIZE) $(CFLAGS)
CXXFLAGS_ALL = -std=c++17 $(COMMON) $(PKG_CFLAGS) $(SANITIZE) $(CXXFLAGS)
LIBS = $(PKG_LIBS) -lstdc++ -lpthread -lm $(SANITIZE) $(LDFLAGS)

# The program's sources: everything under app/ and platform/ except main.c, plus the embedded
# shaders. gpiod_v1.c / gpiod_v2.c: only the one matching the installed libgpiod is built.
GPIOD_SKIP := $(if $(filter 2,$(GPIOD_MAJOR)),platform/gpiod_v1.c,platform/gpiod_v2.c)
C_SRCS   := $(filter-out app/cli/main.c $(GPIOD_SKIP),$(shell find base app platform -name '*.c' | LC_ALL=C sort))
CXX_SRCS := $(shell find base app platform -name '*.cpp' | LC_ALL=C sort)
SHADERS  := $(shell find shaders_gles -type f 2>/dev/null | LC_ALL=C sort)
# the folders too: a file moved out or deleted changes its folder's time, not any file's
SHADER_DIRS := $(shell find shaders_gles -type d 2>/dev/null | LC_ALL=C sort)
GEN_SHADERS := $(BUILD)/gen/shaders_embedded.c

OBJS := $(C_SRCS:%.c=$(BUILD)/obj/%.o) $(CXX_SRCS:%.cpp=$(BUILD)/obj/%.o) $(BUILD)/obj/gen/shaders_embedded.o
LIB  := $(BUILD)/libgikiosk.a
BIN  := $(BUILD)/gikiosk

# Tests: tests/unit/test_*.c link the link-level fakes in tests/fakes/ (libdrm, GBM, libgpiod,
# evdev); tests/gpu/test_*.c run on the real Mesa (llvmpipe) without fakes.
UNIT_SRCS := $(shell find tests/unit -name 'test_*.c' 2>/dev/null | LC_ALL=C sort)
GPU_SRCS  := $(shell find tests/gpu -name 'test_*.c' 2>/dev/null | LC_ALL=C sort)
FAKE_SRCS := $(shell find tests/fakes -name '*.c' 2>/dev/null | LC_ALL=C sort)
TESTLIB_SRCS := $(shell find tests/common -name '*.c' -o -name '*.cpp' 2>/dev/null | LC_ALL=C sort)
UNIT_BINS := $(UNIT_SRCS:tests/%.c=$(BUILD)/tests/%)
GPU_BINS  := $(GPU_SRCS:tests/%.c=$(BUILD)/tests/%)
FAKE_OBJS := $(FAKE_SRCS:%.c=$(BUILD)/obj/%.o)
TESTLIB_OBJS := $(addprefix $(BUILD)/obj/,$(addsuffix .o,$(basename $(TESTLIB_SRCS))))
# Kept after the build: as intermediates make would delete them after the tests and print an
# `rm` line after the suite's closing `N passed, N failed`.
.SECONDARY: $(FAKE_OBJS) $(TESTLIB_OBJS)
# Test-only shaders live in tests/shaders/ (not embedded in the program). The GPU tests load them
# from one root holding both trees, so they #include the production shaders as those do each other:
# $(BUILD)/tests/shaders, a copy of shaders_gles/ with tests/shaders/ laid over it.
TEST_SHADERS := $(shell find tests/shaders -type f 2>/dev/null | LC_ALL=C sort)
TEST_SHADER_STAMP := $(BUILD)/tests/shaders/.stamp
$(TESTLIB_OBJS): CFLAGS_ALL += -DGK_TEST_SHADERS=\"$(abspath $(BUILD))/tests/shaders\"

.PHONY: all run test test-only bench bench-compare calibrate references scenes ltc deps install asan tsan bench-truth fuzz clean shaders-check
all: $(BIN)

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -MMD -MP -c $< -o $@

$(BUILD)/obj/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS_ALL) -MMD -MP -c $< -o $@

$(GEN_SHADERS): $(SHADERS) $(SHADER_DIRS) tools/embed_shaders.sh
	@mkdir -p $(dir $@)
	sh tools/embed_shaders.sh shaders_gles $@

$(BUILD)/obj/gen/shaders_embedded.o: $(GEN_SHADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -c $< -o $@

$(LIB): $(OBJS)
	@rm -f $@
	ar rcs $@ $^

$(BIN): $(BUILD)/obj/app/cli/main.o $(LIB)
	$(CC) $^ -o $@ $(LIBS)

$(BUILD)/tests/unit/%: tests/unit/%.c $(LIB) $(FAKE_OBJS) $(TESTLIB_OBJS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -Itests $< $(FAKE_OBJS) $(TESTLIB_OBJS) $(LIB) -o $@ $(LIBS) -lcmocka

$(TEST_SHADER_STAMP): $(SHADERS) $(SHADER_DIRS) $(TEST_SHADERS)
	rm -rf $(dir $@) && mkdir -p $(dir $@)
	cp -R shaders_gles/. tests/shaders/. $(dir $@)
	touch $@

$(BUILD)/tests/gpu/%: tests/gpu/%.c $(LIB) $(TESTLIB_OBJS) | $(TEST_SHADER_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -Itests $< $(TESTLIB_OBJS) $(LIB) -o $@ $(LIBS) -lcmocka

# The fuzz targets (libFuzzer, clang; tests/fuzz/fuzz_*.c): gltf (the loader from memory),
# gltf_files (the loader from a scene folder: URIs, confinement, file readers), config (kiosk.ini),
# script (button scripts), image (the EXR/PNG readers of `compare`). Built and run briefly by `make
# test` (a fixed number of runs from seed 1, tests/run.sh; FUZZ_TEST_SECONDS caps each); `make fuzz`
# hunts from a random seed for FUZZ_SECONDS each. Only the modules they reach (base, scene, core,
# io, the config and script parsers, the budget they fill) are compiled with clang and the
# sanitizers, and the C++ shims (tinygltf, OpenImageIO) with clang++, into one archive, so each
# target links only what it calls (the commands live in app/cli/, so no exclusions are needed). Of
# app/gi/ only the catalogue of method names comes along: a leaf without GL that scene/ and the
# config read.
FUZZ_TARGETS := gltf gltf_files config script image
FUZZ_BINS := $(FUZZ_TARGETS:%=$(BUILD)/fuzz/fuzz_%)
FUZZ_SRCS := $(filter base/% app/scene/% app/core/% app/io/% app/gi/gi_catalogue.c app/kiosk/config.c \
	app/sched/budget.c platform/script.c,$(C_SRCS) $(CXX_SRCS))
FUZZ_OBJS := $(addprefix $(BUILD)/fuzzobj/obj/,$(addsuffix .o,$(basename $(FUZZ_SRCS))))
FUZZ_LIB  := $(BUILD)/fuzzobj/libfuzzed.a
FUZZ_HDRS := $(wildcard base/*.h app/scene/*.h app/core/*.h app/io/*.h app/kiosk/config.h app/sched/budget.h \
	platform/platform.h platform/script.h platform/gesture.h) app/gi/gi_catalogue.h tests/fuzz/fuzz_files.h
FUZZ_SECONDS ?= 60
FUZZ_TEST_SECONDS ?= 120
$(FUZZ_LIB): $(FUZZ_SRCS) $(FUZZ_HDRS)
	@mkdir -p $(dir $@)
	$(MAKE) --no-print-directory BUILD=$(BUILD)/fuzzobj CC=clang CXX=clang++ OPT=-O1 WERROR= \
		SANITIZE="-fsanitize=fuzzer-no-link,address,undefined" $(FUZZ_OBJS)
	rm -f $@ && ar rcs $@ $(FUZZ_OBJS)
$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_LIB)
	@mkdir -p $(dir $@)
	clang $(filter-out -Werror,$(CFLAGS_ALL)) -fsanitize=fuzzer-no-link,address,undefined -c $< \
		-o $(BUILD)/fuzzobj/fuzz_$*.o
	@# linked by clang++ so UBSan's C++ runtime (vptr checks of the shims) comes along
	clang++ -fsanitize=fuzzer,address,undefined $(BUILD)/fuzzobj/fuzz_$*.o $(FUZZ_LIB) -o $@ \
		$(PKG_LIBS) -lpthread -lm
# Runs every target for FUZZ_SECONDS on a copy of its seed corpus (tests/fuzz/corpus/TARGET/);
# findings are kept under $(BUILD)/fuzz-artifacts/.
fuzz: $(FUZZ_BINS)
	@for t in $(FUZZ_TARGETS); do BUILD=$(BUILD) sh tests/fuzz/run_fuzz.sh $(BUILD)/fuzz/fuzz_$$t $(FUZZ_SECONDS) || exit 1; done

# libgpiod 2.x compile check on Debian 12 (only 1.6 there): bookworm-backports debs unpacked into
# $(BUILD)/gpiod2/, platform/gpiod_v2.c compiled against them; skips cleanly when offline.
.PHONY: gpiod2-check
gpiod2-check:
	sh tools/gpiod2-prefix.sh $(BUILD)

# ---------------------------------------------------------------------------------------------
deps:
	@sh tools/deps.sh $(DEB_PACKAGES)

run: deps $(BIN)
	sh tools/showcase.sh $(BIN)

test: deps
	@$(MAKE) --no-print-directory test-only

test-only: $(BIN) $(UNIT_BINS) $(GPU_BINS) $(if $(NO_FUZZ),,$(FUZZ_BINS))
	@FUZZ_TEST_SECONDS=$(FUZZ_TEST_SECONDS) sh tests/run.sh $(BUILD)

# AddressSanitizer + UBSan over the whole suite. Leak checking stays on for the unit tests; in the
# programs that run Mesa (gpu tests, the binary in e2e tests) it is off, because llvmpipe's worker
# threads report two 56-byte allocations of their own at exit (from JIT code that the fast unwinder
# cannot name, so no suppression can match them; with fast_unwind_on_malloc=0 they are not reported,
# but that makes the GPU tests 20x slower). Memory errors and UB are still checked everywhere.
asan: deps
	@GK_MESA_ASAN_OPTIONS=detect_leaks=0 $(MAKE) --no-print-directory BUILD=build-asan OPT=-O1 NO_FUZZ=1 \
		SANITIZE="-fsanitize=address,undefined -fno-omit-frame-pointer" test-only

# ThreadSanitizer over the threads of the kiosk's live ground truth (app/kiosk/truth.c): the truth's
# unit test and the kiosk running with [truth] enabled on the mock platform (tools/tsan.sh). Mesa's
# own races (llvmpipe's threads, inside the driver) are suppressed in tests/tsan.supp, nothing else.
tsan: deps
	@$(MAKE) --no-print-directory BUILD=build-tsan OPT=-O1 NO_FUZZ=1 SANITIZE="-fsanitize=thread" \
		build-tsan/gikiosk build-tsan/tests/unit/test_truth
	sh tools/tsan.sh build-tsan

bench: deps $(BIN) $(BUILD)/tests/gpu/test_lgv
	sh tools/bench.sh $(BIN) $(BUILD)/tests/gpu/test_lgv

# The frame time with the live ground truth's workers on against off, runs interleaved (ratios).
bench-truth: deps $(BIN)
	sh tools/truth_bench.sh $(BIN)

# This tree against an earlier commit, runs interleaved (tools/bench_compare.sh): per-pass ratios.
# make bench-compare REV=<commit> [COMPARE_ARGS="--scene cornell --size 640x360 --runs 5"]
bench-compare: deps $(BIN)
	sh tools/bench_compare.sh $(BIN) "$(REV)" $(COMPARE_ARGS)

# The measured model the kiosk chooses methods from: config/calibration/CLASS.csv (tools/calibrate.sh).
calibrate: deps $(BIN)
	sh tools/calibrate.sh $(BIN)

references: deps $(BIN)
	sh tools/references.sh $(BIN)

scenes: deps $(BIN)
	$(BIN) build-scenes config/scenes

# The LTC tables of the rectangle lights' GGX term (tools/ltc_fit.c, about 2.5 minutes): rewrites
# app/render/ltc_table.c, which is committed.
ltc: $(BUILD)/tools/ltc_fit
	$(BUILD)/tools/ltc_fit app/render/ltc_table.c

$(BUILD)/tools/ltc_fit: tools/ltc_fit.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 -O2 -Wall -Wextra $(WERROR) $< -o $@ -lm

install: $(BIN)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/gikiosk/scenes \
		$(DESTDIR)$(PREFIX)/share/gikiosk/calibration $(DESTDIR)/etc/gikiosk \
		$(DESTDIR)/lib/systemd/system $(DESTDIR)/lib/udev/rules.d
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/gikiosk
	install -m 644 config/scenes/* $(DESTDIR)$(PREFIX)/share/gikiosk/scenes/
	install -m 644 config/calibration/*.csv $(DESTDIR)$(PREFIX)/share/gikiosk/calibration/
	install -m 644 config/kiosk.ini $(DESTDIR)/etc/gikiosk/kiosk.ini
	install -m 644 board/gikiosk.service $(DESTDIR)/lib/systemd/system/gikiosk.service
	install -m 644 board/99-gikiosk.rules $(DESTDIR)/lib/udev/rules.d/99-gikiosk.rules

clean:
	rm -rf build build-asan build-tsan out

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
