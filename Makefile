# `make demo` and `make test` work on a fresh Debian 12 machine (no GPU needed): both first install any missing
# system packages (.ci/deps.sh), then build with cargo.

CARGO ?= cargo

# Tests run on lavapipe (Mesa's CPU Vulkan driver) unless DNSR_DEVICE names another device, e.g.
# `make test DNSR_DEVICE=NVIDIA`.
DNSR_DEVICE ?= llvmpipe

.PHONY: all demo test bench shaders deps clean

all: test

deps:
	.ci/deps.sh

# Denoises a synthetic sequence; writes out/demo/{noisy,denoised,truth,strip}.png and report.md.
# Runs on whatever Vulkan device exists (DNSR_DEVICE from the environment picks one by name).
demo: deps
	$(CARGO) run --release --features demo --bin dnsr-demo -- --out out/demo

# Every test, with the validation layer and synchronization validation: any message fails a test.
# Also builds the demo, so a change that breaks it fails here rather than at a user's `make demo`.
test: deps
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" $(CARGO) test --release
	$(CARGO) build --release --features demo --bins
	@# dnsr loads Vulkan through the host's vkGetInstanceProcAddr: the shared library must not link the loader.
	@if ldd target/release/libdnsr.so | grep -q libvulkan; then echo "libdnsr.so links libvulkan"; exit 1; fi
	@echo "libdnsr.so does not link libvulkan"

# Median GPU timings per pass on synthetic scenes (run it on the GPU you want numbers for).
bench: deps
	$(CARGO) run --release --features demo --bin dnsr-bench

# Regenerates shaders/generated/dnsr_constants.glsl and shaders/spv/*.spv (needs glslc).
shaders: deps
	DNSR_BLESS=1 $(CARGO) test --release --lib bless_

clean:
	$(CARGO) clean
	rm -rf out
