// The specialization constants of the passes (ids generated from src/passes/mod.rs). Included by dnsr_storage.glsl,
// whose signal codec tests for a final receiver's code only where one can be stored, and by dnsr_common.glsl.
#ifndef DNSR_SPECIALIZATION_GLSL
#define DNSR_SPECIALIZATION_GLSL

#include "generated/dnsr_constants.glsl"

// Features only some frames use are specialization constants (ids generated from src/passes/mod.rs, which says
// why): the host binds the pipeline specialized for what the frame uses, and the others run without that code.
// Each is declared only by the passes that use it: the host reads from the SPIR-V which ones a pass has and
// compiles a pipeline per combination.
#if defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER)
// Penumbra guidance: the dispatch has hit distances.
layout(constant_id = DNSR_SPEC_ID_PENUMBRA_GUIDED) const bool DNSR_SPEC_PENUMBRA_GUIDED = false;
// The run features: Settings::stable_history_samples > 0 (dnsr_get_run_settings().x) or converged_samples > 0 (.z).
// The filter passes look for final pixels (dnsr_final_signal) only with them: classification writes none without.
layout(constant_id = DNSR_SPEC_ID_STABLE_HISTORY) const bool DNSR_SPEC_STABLE_HISTORY = false;
#endif
#ifdef DNSR_PASS_TILE_CLASSIFICATION
// A shadow moving over a still surface is told (Settings::moving_shadow_sigmas > 0, with the run features).
layout(constant_id = DNSR_SPEC_ID_MOVING_SHADOWS) const bool DNSR_SPEC_MOVING_SHADOWS = false;
#endif
#if defined(DNSR_PASS_TILE_CLASSIFICATION) || (defined(DNSR_PASS_FILTER) && !defined(DNSR_LATER_PASS))
// The light has no size (ShadowsDispatch::hard_light): every receiver's own sample is its output.
layout(constant_id = DNSR_SPEC_ID_HARD_LIGHT) const bool DNSR_SPEC_HARD_LIGHT = false;
#endif

// Whether a stored signal can hold a final receiver's code: classification writes final receivers only with the run
// features, so every other pipeline (Balanced's) compiles its signal codec and filter without the test. Balanced
// paid 0.022 ms at 4K on an H100 for final pixels it never has while the codec tested for them whatever the constant
// (docs/bench/h200-2026-12-07-final-pixels); with this gate its later passes took 0.013 ms less each
// (docs/bench/h100-2026-12-08-spec-gates).
bool dnsr_stores_finals() {
#if defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER)
    return DNSR_SPEC_STABLE_HISTORY;
#else
    return false;
#endif
}

#endif
