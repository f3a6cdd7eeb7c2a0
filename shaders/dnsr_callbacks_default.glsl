// dnsr default callbacks: what the pass entry files include. dnsr's own variants use the standard callbacks over
// its bindings; an engine compiling the passes against its own G-buffer encoding replaces this file in a copy of
// the sources (docs/callbacks.md, examples-c/custom_gbuffer).
#include "dnsr_callbacks_standard.glsl"
