# `make demo` and `make test` work on a fresh Debian 12 machine (no GPU needed): both first install any missing
# system packages (.ci/deps.sh), then build with cargo.

CARGO ?= cargo

# Tests run on lavapipe (Mesa's CPU Vulkan driver) unless DNSR_DEVICE names another device, e.g.
# `make test DNSR_DEVICE=NVIDIA`.
DNSR_DEVICE ?= llvmpipe

.PHONY: all demo test shaders deps clean

all: test

deps:
	.ci/deps.sh

# Denoises a synthetic sequence; writes out/demo/{noisy,denoised,truth,strip}.png and report.md.
# Runs on whatever Vulkan device exists (DNSR_DEVICE from the environment picks one by name).
demo: deps
	$(CARGO) run --release --features demo --bin dnsr-demo -- --out out/demo

# Every test, with the validation layer and synchronization validation: any message fails a test.
test: deps
	env -u VK_LOADER_DEBUG DNSR_DEVICE="$(DNSR_DEVICE)" $(CARGO) test --release

# Regenerates shaders/generated/dnsr_constants.glsl and shaders/spv/*.spv (needs glslc).
shaders:
	DNSR_BLESS=1 $(CARGO) test --release --lib bless_

clean:
	$(CARGO) clean
	rm -rf out
