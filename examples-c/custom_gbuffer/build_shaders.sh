#!/usr/bin/env bash
# Compiles the pass variants custom_gbuffer.c overrides from dnsr's installed shader sources with this
# directory's engine_callbacks.glsl, as an engine's build would.
#   build_shaders.sh <prefix>/share/dnsr/shaders OUT_DIR [c]
# writes OUT_DIR/<variant>.spv, or with `c` OUT_DIR/<variant>.inc (C initialiser lists, glslc -mfmt=c, which the
# viewer's build embeds).
# The variants are those of an FP32 context with an R32_SFLOAT output (dnsr_get_shader_variants lists every
# variant with its entry file and definitions), and the classifier's variant for separate cascade images; prepare
# reads no G-buffer and keeps dnsr's own SPIR-V.
set -euo pipefail
shaders=$1 out=$2 format=${3:-spv}
case $format in
spv) extra=() suffix=spv ;;
c) extra=(-mfmt=c) suffix=inc ;;
*) echo "build_shaders.sh: the third argument is c or nothing, not '$format'" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$out/src"
cp -r "$shaders/." "$out/src/"
cp "$here/engine_callbacks.glsl" "$out/src/dnsr_callbacks_default.glsl"
compile() { # compile NAME ENTRY DEFINES...
    local name=$1 entry=$2
    shift 2
    glslc --target-env=vulkan1.1 -I"$out/src" "${extra[@]}" "$@" "$out/src/$entry" -o "$out/$name.$suffix"
}
compile tile_classification_r32f tile_classification.comp -DDNSR_OUTPUT_FORMAT=r32f
compile filter filter.comp
compile filter_later filter.comp -DDNSR_LATER_PASS
compile filter_final_r32f filter.comp -DDNSR_FINAL_PASS -DDNSR_OUTPUT_FORMAT=r32f
compile filter_later_final_r32f filter.comp -DDNSR_LATER_PASS -DDNSR_FINAL_PASS -DDNSR_OUTPUT_FORMAT=r32f
# The hybrid-shadows classifier reads depth and normals too (the viewer's --hybrid --gbuffer packed uses it).
compile classify classify.comp
echo "custom_gbuffer: 6 variants compiled into $out"
