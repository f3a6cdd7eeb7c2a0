/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the utility macros an integration's glue code uses.
 *
 * Written for dnsr from the SDK's interface (names and meanings); with include/ffx ahead of the SDK's include
 * folder this header is found instead of the SDK's, which needs the SDK's own mutex definitions.
 */
#ifndef FFX_UTIL_H
#define FFX_UTIL_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "ffx_types.h"

#ifdef __cplusplus
static const float FFX_PI = 3.141592653589793f;
static const float FFX_EPSILON = 1e-06f;
#else
#define FFX_PI 3.141592653589793f
#define FFX_EPSILON 1e-06f
#endif

/* FFX_MAKE_VERSION is in ffx_types.h. */
#define FFX_UNSPECIFIED_VERSION 0xFFFFAD00

/* Silences an unused-variable warning (evaluates x). */
#define FFX_UNUSED(x) ((void)(x))
/* x rounded up to a multiple of the power of two y. */
#define FFX_ALIGN_UP(x, y) (((x) + ((y) - 1)) & ~((y) - 1))
/* Unsigned division rounded up. */
#define FFX_DIVIDE_ROUNDING_UP(x, y) (((x) + (y) - 1) / (y))
#define FFX_STR(s) FFX_XSTR(s)
#define FFX_XSTR(s) #s
#define FFX_FORWARD_DECLARE(x) typedef struct x x
#define FFX_MAXIMUM(x, y) (((x) > (y)) ? (x) : (y))
#define FFX_MINIMUM(x, y) (((x) < (y)) ? (x) : (y))
#define FFX_ABSOLUTE(x) (((x) < 0) ? (-(x)) : (x))
#define FFX_SIGN(x) (((x) < 0) ? -1 : 1)
#define FFX_SAFE_FREE(x) \
    if (x)               \
    free(x)
/* The number of elements of an array (not of a pointer: sizeof of a pointer is no multiple of its element's in
 * general, and the division by zero that follows then stops the compiler). */
#define FFX_ARRAY_ELEMENTS(x) (int32_t)((sizeof(x) / sizeof(0 [x])) / ((size_t)(!(sizeof(x) % sizeof(0 [x])))))
#define FFX_MAXIMUM_PATH (260)
/* Whether every bit of key is set in options. */
#define FFX_CONTAINS_FLAG(options, key) (((options) & (key)) == (key))

#endif
