// Arithmetic and storage precision of the filter path, chosen per compiled variant.
// DNSR_FP16: the a-trous filter works in float16 and the intermediate images are R16G16_SFLOAT (the history, their
// mean alone, R16_SFLOAT); otherwise it works in float32 and they are R16G16_UNORM (the history R16_UNORM;
// dnsr_storage.glsl, dnsr_encode_signal).
#ifndef DNSR_PRECISION_GLSL
#define DNSR_PRECISION_GLSL

#ifdef DNSR_FP16
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#define DNSR_INTERMEDIATE_FORMAT rg16f
#define DNSR_HISTORY_FORMAT r16f
#define real float16_t
#define real2 f16vec2
#define real3 f16vec3
#else
#define DNSR_INTERMEDIATE_FORMAT rg16
#define DNSR_HISTORY_FORMAT r16
#define real float
#define real2 vec2
#define real3 vec3
#endif

#endif
