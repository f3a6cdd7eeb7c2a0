# `make demo` and `make test` work on a fresh Debian 12 machine (no GPU needed): both first install any missing
# system packages (.ci/deps.sh), then build with cargo.

CARGO ?= cargo

# Tests run on lavapipe (Mesa's CPU Vulkan driver) unless DNSR_DEVICE names another device, e.g.
# `make test DNSR_DEVICE=NVIDIA`.
DNSR_DEVICE ?= llvmpipe

.PHONY: all demo demo-synthetic viewer viewer-accuracy viewer-hybrid test bench bench-smoke accuracy generate shaders header deps clean

all: test

deps:
	.ci/deps.sh

# The C++ viewer, headless, on its default glTF scene: ray-traced 1-spp soft shadows denoised by dnsr through the
# C API. Writes out/demo/{noisy,denoised,reference,composite,strip,tiles}.png and report.json (GPU ms, RMSE/PSNR
# against a 256-ray reference). Runs on whatever Vulkan device exists (VIEWER_DEVICE=<name> picks one).
demo: viewer
	build/viewer/dnsr_viewer --headless --frames 16 --size 640x384 --out out/demo

# Builds the viewer (examples-c/viewer) against the freshly built library.
viewer: deps
	$(CARGO) build --release --lib
	cmake -S examples-c/viewer -B build/viewer -DCMAKE_BUILD_TYPE=Release -DDNSR_LIB="$(CURDIR)/target/release/libdnsr.so"
	cmake --build build/viewer -j

# The synthetic, truth-known sequence of the Rust demo: out/demo-synthetic/{noisy,denoised,truth,strip}.png.
demo-synthetic: deps
	$(CARGO) run --release --features demo --bin dnsr-demo -- --out out/demo-synthetic

# Every test, with the validation layer and synchronization validation: any message fails a test.
# Also builds the demo, so a change that breaks it fails here rather than at a user's `make demo`.
test: deps
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" $(CARGO) test --release
	$(CARGO) build --release --features demo --bins
	@# The benchmark at a tiny size, every scene, preset and precision, under validation: it must run cleanly and
	@# write valid bench.json / bench.md (no timing is checked).
	$(MAKE) bench-smoke
	@# dnsr loads Vulkan through the host's vkGetInstanceProcAddr: the shared library must not link the loader.
	@if ldd target/release/libdnsr.so | grep -q libvulkan; then echo "libdnsr.so links libvulkan"; exit 1; fi
	@echo "libdnsr.so does not link libvulkan"
	@# The C/C++ code compiled in (SPIRV-Reflect, SPIRV-Tools) must not be able to abort the host on bad SPIR-V.
	@if nm -D target/release/libdnsr.so | grep -q __assert_fail; then echo "libdnsr.so calls assert (build with .cargo/config.toml's -DNDEBUG)"; exit 1; fi
	@echo "libdnsr.so has no assert"
	@# The C ABI: header (C11, C++17) and layout, bad-input matrix, a full frame, the minimal example, all under
	@# AddressSanitizer and the validation layer; then the install story (pkg-config, CMake consumer, soname).
	DNSR_DEVICE="$(DNSR_DEVICE)" capi-tests/run.sh
	capi-tests/install/check.sh
	@# The C++ viewer: headless on lavapipe with validation, windowed under Xvfb, and every bad-glTF case.
	VIEWER_DEVICE="$(DNSR_DEVICE)" examples-c/viewer/test.sh

# "Do no harm" on the procedural scene family (examples-c/viewer/family.py, scenes/make_family.py): FAMILY_SCENES
# seeded scenes, each with its own light and camera, every preset without penumbra guidance and Quality with it, as
# distributions -> docs/viewer-family.md.
FAMILY_SCENES ?= 100
# The same checks on objects the methods were not developed on (make_family.py's `unseen` vocabulary, seeds from
# 5000): docs/viewer-family-unseen.md. A check of whether the methods carry over; never tune on it.
UNSEEN_SCENES ?= 50
# The viewer's committed scenes (default, thin fins, thin shells) against their 1024-ray reference, every preset,
# directional and point light, still and orbiting camera: writes docs/viewer-accuracy.md (a few minutes on lavapipe).
viewer-accuracy: viewer
	examples-c/viewer/accuracy.py build/viewer/dnsr_viewer docs/viewer-accuracy.md
	python3 examples-c/viewer/family.py build/viewer/dnsr_viewer build/family --count $(FAMILY_SCENES) \
		--presets fast,balanced,quality,quality+untold,quality+guided --md docs/viewer-family.md
	python3 examples-c/viewer/family.py build/viewer/dnsr_viewer build/family-unseen --first 5000 --count $(UNSEEN_SCENES) \
		--objects unseen --presets fast,balanced,quality,quality+untold,quality+guided --md docs/viewer-family-unseen.md

# Hybrid shadows against full tracing on the viewer's committed scenes (examples-c/viewer/hybrid.py): rays traced,
# rays saved, GPU ms and RMSE against a 1024-ray reference, into out/hybrid/hybrid.md. docs/hybrid-shadows.md has the
# H100 tables (with held-out scenes too); on lavapipe use a small size, e.g. HYBRID_SIZES=320x192.
HYBRID_SIZES ?= 1920x1080,3840x2160
viewer-hybrid: viewer
	python3 examples-c/viewer/hybrid.py build/viewer/dnsr_viewer out/hybrid --sizes $(HYBRID_SIZES) --suns 0.27,3 \
	  examples-c/viewer/scenes/default.gltf examples-c/viewer/scenes/fins.gltf examples-c/viewer/scenes/shells.gltf

# Truth-known quality harness: writes docs/accuracy.md and docs/accuracy/*.png (presets, knob sweeps, images).
accuracy: deps
	$(CARGO) run --release --features demo --bin dnsr-accuracy -- --out docs

# The benchmark (BENCHMARKS.md): every size x scene x preset x precision, each after a warm-up (>= 20 frames and 1 s,
# then until the GPU time is stable) over 200 timed frames, with the copy roofline and the byte model; writes
# out/bench/bench.json and bench.md. Run it on the GPU you want numbers for (DNSR_DEVICE=<name> picks one);
# BENCH_ARGS restricts it, e.g. BENCH_ARGS="--sizes 3840x2160 --presets balanced".
BENCH_ARGS ?=
bench: deps
	$(CARGO) run --release --features demo --bin dnsr-bench -- --out out/bench $(BENCH_ARGS)

# Part of `make test`: dnsr-bench at 64x32 with validation, then a check of its JSON.
bench-smoke:
	$(CARGO) build --release --features demo --bin dnsr-bench
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" target/release/dnsr-bench --sizes 64x32 --frames 3 --warmup 1 \
		--warmup-ms 0 --copy-mib 8 --copy-runs 3 --validation --out out/bench-smoke > /dev/null
	python3 -c 'import json, math; d = json.load(open("out/bench-smoke/bench.json")); \
		r = d["results"]; n = 4 * 3 * (1 if d["device"]["float16"] is False else 2); \
		assert len(r) == n, f"{len(r)} results instead of {n}"; \
		assert all(math.isfinite(x["total"]["median_ms"]) and len(x["passes"]) == 2 + x["filter_passes"] for x in r); \
		assert all(0 < x["persistent_memory_bytes"] < x["memory_bytes"] for x in r); \
		assert d["copy_bandwidth"]["gbps_median"] > 0; \
		open("out/bench-smoke/bench.md").read(); print(f"bench smoke: {len(r)} configurations, valid bench.json")'
	@# BENCHMARKS.md's byte model is the one the bench runs (derived from the state table): a format or an access
	@# changed there changes the documented table too.
	python3 -c 'import sys; \
		table = lambda t: [l for l in t[t.index("| pass | resource |"):].split("\n\n")[0].splitlines()]; \
		doc = open("BENCHMARKS.md").read(); doc = doc[doc.index("## Byte model"):]; \
		sys.exit(0 if table(doc) == table(open("out/bench-smoke/bench.md").read()) else \
			"BENCHMARKS.md: the byte model table differs from the one dnsr-bench prints (out/bench-smoke/bench.md): copy it over")'
	@echo "bench smoke: BENCHMARKS.md's byte model is the bench's"
	@# --shader-override with dnsr's own SPIR-V for two variants: the override path under validation, and a bad
	@# variant name refused with the context's error.
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" target/release/dnsr-bench --sizes 64x32 --scenes typical \
		--presets quality --precisions fp32 --frames 3 --warmup 1 --warmup-ms 0 --copy-mib 8 --copy-runs 1 --validation \
		--shader-override tile_classification_r16f=shaders/spv/tile_classification_r16f.spv \
		--shader-override filter=shaders/spv/filter.spv --out out/bench-smoke-override > /dev/null
	grep -q -- "--shader-override filter=" out/bench-smoke-override/bench.md
	! target/release/dnsr-bench --sizes 64x32 --scenes typical --presets quality --precisions fp32 --frames 1 \
		--warmup 0 --warmup-ms 0 --copy-mib 8 --copy-runs 1 --shader-override no_such_variant=shaders/spv/filter.spv \
		--out out/bench-smoke-bad 2> out/bench-smoke-bad.log > /dev/null
	grep -q "not a dnsr shader variant" out/bench-smoke-bad.log
	@echo "bench smoke: --shader-override runs and refuses an unknown variant"
	@# --host-previous under validation; its byte model reads the host's previous depth (and with the run features
	@# its normals) where classification read the depth copy: Quality's classification reads more than without it.
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" target/release/dnsr-bench --sizes 64x32 --scenes typical \
		--presets quality --precisions fp32 --frames 3 --warmup 1 --warmup-ms 0 --copy-mib 8 --copy-runs 1 --validation \
		--host-previous --out out/bench-smoke-host-previous > /dev/null
	python3 -c 'import json; \
		cls = lambda f: [x["passes"][1]["model_read_bytes"] for x in json.load(open(f))["results"] \
			if x["scene"] == "typical" and x["preset"] == "quality" and x["precision"] == "fp32"][0]; \
		own, host = cls("out/bench-smoke/bench.json"), cls("out/bench-smoke-host-previous/bench.json"); \
		assert host > own * 1.05, (own, host); print(f"bench smoke: --host-previous, classification reads {own:.0f} -> {host:.0f} B")'

# Regenerates every generated, committed file: shaders/generated/dnsr_constants.glsl, shaders/spv/*.spv (needs
# glslc), include/dnsr.h (cbindgen) and capi-tests/generated/layout.h. `make test` fails when any is stale.
generate: deps
	DNSR_BLESS=1 $(CARGO) test --release --lib bless_
shaders header: generate

clean:
	$(CARGO) clean
	rm -rf out

# Installs the C library: libdnsr.so.<version> (soname libdnsr.so.<abi>, plus the libdnsr.so.<abi> and
# libdnsr.so links), libdnsr.a, dnsr.h, the FidelityFX compatibility headers (include/dnsr-ffx), dnsr.pc for
# pkg-config, a CMake package (find_package(dnsr) -> dnsr::dnsr, and dnsr::ffx for FFX integrations) and the
# shader sources (share/dnsr/shaders, for engines compiling the passes with their own callbacks). `make install PREFIX=$HOME/.local`, or for packaging `make install PREFIX=/usr DESTDIR=$pkgdir`.
# `make uninstall` (same PREFIX/LIBDIR/INCLUDEDIR/DESTDIR) removes exactly those files.
PREFIX ?= /usr/local
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
DESTDIR ?=
# The version is written once, in Cargo.toml's [package]. <abi> is 0.<minor> for 0.x and <major> from 1.0 on:
# the same rule as src/build.rs (which sets the soname) and the CMake version file.
DNSR_VERSION := $(shell sed -n '/^\[package\]/,/^\[/s/^version *= *"\([^"]*\)".*/\1/p' Cargo.toml)
DNSR_MAJOR := $(word 1,$(subst ., ,$(DNSR_VERSION)))
DNSR_MINOR := $(word 2,$(subst ., ,$(DNSR_VERSION)))
DNSR_ABI := $(if $(filter 0,$(DNSR_MAJOR)),0.$(DNSR_MINOR),$(DNSR_MAJOR))
DNSR_TARGET_DIR := $(or $(CARGO_TARGET_DIR),target)
DNSR_CMAKEDIR := $(LIBDIR)/cmake/dnsr
DNSR_TEMPLATES := capi-tests/install/templates
DNSR_FFX_HEADERS := $(wildcard include/ffx/FidelityFX/host/*.h)
DNSR_SHADER_SOURCES := $(wildcard shaders/*.glsl shaders/*.comp)
DATADIR ?= $(PREFIX)/share
DNSR_SHADERDIR := $(DATADIR)/dnsr/shaders
# Template substitutions; in dnsr.pc, libdir and includedir are written relative to ${prefix} when under it.
DNSR_SED := -e 's|@VERSION@|$(DNSR_VERSION)|g' -e 's|@ABI@|$(DNSR_ABI)|g' \
	-e 's|@PREFIX@|$(PREFIX)|g' \
	-e 's|@LIBDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))|g' \
	-e 's|@INCLUDEDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(INCLUDEDIR))|g' \
	-e "s|@REL_INCLUDEDIR@|$$(realpath -m --relative-to='$(DNSR_CMAKEDIR)' '$(INCLUDEDIR)')|g" \
	-e "s|@SIZEOF_VOID_P@|$$(($$(getconf LONG_BIT) / 8))|g"

.PHONY: install uninstall

install:
	@test -n "$(DNSR_VERSION)" || { echo "no version in Cargo.toml [package]"; exit 1; }
	$(CARGO) build --release --lib
	install -d '$(DESTDIR)$(LIBDIR)' '$(DESTDIR)$(INCLUDEDIR)' '$(DESTDIR)$(LIBDIR)/pkgconfig' '$(DESTDIR)$(DNSR_CMAKEDIR)'
	install -m 755 '$(DNSR_TARGET_DIR)/release/libdnsr.so' '$(DESTDIR)$(LIBDIR)/libdnsr.so.$(DNSR_VERSION)'
	ln -sfn 'libdnsr.so.$(DNSR_VERSION)' '$(DESTDIR)$(LIBDIR)/libdnsr.so.$(DNSR_ABI)'
	ln -sfn 'libdnsr.so.$(DNSR_ABI)' '$(DESTDIR)$(LIBDIR)/libdnsr.so'
	install -m 644 '$(DNSR_TARGET_DIR)/release/libdnsr.a' '$(DESTDIR)$(LIBDIR)/libdnsr.a'
	install -m 644 include/dnsr.h '$(DESTDIR)$(INCLUDEDIR)/dnsr.h'
	@# The FidelityFX SDK 1.1.4 compatibility headers, under their own directory: an FFX integration puts
	@# $(INCLUDEDIR)/dnsr-ffx on its include path in place of the SDK's.
	install -d '$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host/backends/vk'
	install -m 644 $(DNSR_FFX_HEADERS) '$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host'
	install -m 644 include/ffx/FidelityFX/host/backends/vk/ffx_vk.h '$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host/backends/vk'
	@# The shader sources, for engines that compile the passes against their own callbacks (docs/callbacks.md).
	install -d '$(DESTDIR)$(DNSR_SHADERDIR)/generated'
	install -m 644 $(DNSR_SHADER_SOURCES) '$(DESTDIR)$(DNSR_SHADERDIR)'
	install -m 644 shaders/generated/dnsr_constants.glsl '$(DESTDIR)$(DNSR_SHADERDIR)/generated'
	sed $(DNSR_SED) $(DNSR_TEMPLATES)/dnsr.pc.in > '$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr.pc'
	sed $(DNSR_SED) $(DNSR_TEMPLATES)/dnsr-ffx.pc.in > '$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr-ffx.pc'
	sed $(DNSR_SED) $(DNSR_TEMPLATES)/dnsrConfig.cmake.in > '$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfig.cmake'
	sed $(DNSR_SED) $(DNSR_TEMPLATES)/dnsrConfigVersion.cmake.in > '$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfigVersion.cmake'
	chmod 644 '$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr.pc' '$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr-ffx.pc' '$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfig.cmake' '$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfigVersion.cmake'
	@echo "installed dnsr $(DNSR_VERSION) (soname libdnsr.so.$(DNSR_ABI)) to $(DESTDIR)$(PREFIX)"

uninstall:
	rm -f '$(DESTDIR)$(LIBDIR)/libdnsr.so.$(DNSR_VERSION)' '$(DESTDIR)$(LIBDIR)/libdnsr.so.$(DNSR_ABI)' \
		'$(DESTDIR)$(LIBDIR)/libdnsr.so' '$(DESTDIR)$(LIBDIR)/libdnsr.a' '$(DESTDIR)$(INCLUDEDIR)/dnsr.h' \
		'$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr.pc' '$(DESTDIR)$(LIBDIR)/pkgconfig/dnsr-ffx.pc' \
		'$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfig.cmake' \
		'$(DESTDIR)$(DNSR_CMAKEDIR)/dnsrConfigVersion.cmake'
	rm -f $(addprefix '$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host/,$(addsuffix ',$(notdir $(DNSR_FFX_HEADERS)))) \
		'$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host/backends/vk/ffx_vk.h'
	rmdir -p '$(DESTDIR)$(INCLUDEDIR)/dnsr-ffx/FidelityFX/host/backends/vk' 2>/dev/null || true
	rm -f $(addprefix '$(DESTDIR)$(DNSR_SHADERDIR)/,$(addsuffix ',$(notdir $(DNSR_SHADER_SOURCES)))) \
		'$(DESTDIR)$(DNSR_SHADERDIR)/generated/dnsr_constants.glsl'
	rmdir -p '$(DESTDIR)$(DNSR_SHADERDIR)/generated' 2>/dev/null || true
	rmdir '$(DESTDIR)$(DNSR_CMAKEDIR)' 2>/dev/null || true
