#!/usr/bin/env bash
# Installs what dnsr's build, tests and demo need on a Debian 12 machine, skipping what is already there.
# Safe to run repeatedly: when every package is installed it only checks and exits.
set -euo pipefail

PACKAGES=(
    mesa-vulkan-drivers     # lavapipe: a CPU Vulkan device for machines without a GPU
    libvulkan1              # the Vulkan loader (the demo and tests dlopen it; the library never links it)
    libvulkan-dev
    vulkan-validationlayers # VK_LAYER_KHRONOS_validation, on in every test
    glslc                   # GLSL -> SPIR-V (make shaders)
    spirv-tools
    cmake
    pkg-config
    gcc                     # capi-tests and examples-c (C11, with AddressSanitizer)
    g++                     # capi-tests header check as C++17
    binutils                # readelf: soname and NEEDED checks of the install test
    libglfw3-dev
    libtinygltf-dev
    libstb-dev              # the viewer's PNGs (stb_image_write; libstb0 comes with tinygltf already)
    nlohmann-json3-dev      # the viewer's report.json
    xvfb                    # the viewer's windowed test (xvfb-run)
    python3                 # the viewer test checks PNGs and report.json
)

installed() {
    dpkg -s "$1" 2>/dev/null | grep -q '^Status: install ok installed$'
}

missing=()
for p in "${PACKAGES[@]}"; do
    installed "$p" || missing+=("$p")
done

if ((${#missing[@]})); then
    echo "deps: installing ${missing[*]}"
    SUDO=()
    if [[ $(id -u) -ne 0 ]]; then
        command -v sudo >/dev/null || { echo "deps: not root and no sudo; install as root: ${missing[*]}" >&2; exit 1; }
        SUDO=(sudo)
    fi
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
    echo "deps: system packages present"
fi

if ! command -v cargo >/dev/null; then
    if [[ -x "$HOME/.cargo/bin/cargo" ]]; then
        echo "deps: cargo is installed in ~/.cargo/bin but not on PATH: run 'source \"\$HOME/.cargo/env\"'" >&2
    else
        echo "deps: cargo not found: install a Rust toolchain with rustup (https://rustup.rs):" >&2
        echo "  curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh" >&2
    fi
    exit 1
fi
