/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: asserts, as the SDK's glue code uses them.
 *
 * Written for dnsr from the SDK's interface. With _DEBUG defined a failed FFX_ASSERT reports through
 * ffxAssertReport (libdnsr: to the callback ffxAssertSetPrintingCallback set, else to stderr); without it the
 * condition is evaluated and ignored, as in the SDK.
 */
#ifndef FFX_ASSERT_H
#define FFX_ASSERT_H

#include <stdbool.h>
#include <stdint.h>

#include "ffx_types.h"
#include "ffx_util.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Receives the text of a failed assert. */
typedef void (*FfxAssertCallback)(const char *message);

/* Reports a failed assert (condition and msg may be NULL); returns true. */
FFX_API bool ffxAssertReport(const char *file, int32_t line, const char *condition, const char *msg);
/* Routes assert reports to `callback` (NULL: stderr). */
FFX_API void ffxAssertSetPrintingCallback(FfxAssertCallback callback);

#define FFX_DEBUG_BREAK

#ifdef _DEBUG
#define FFX_ASSERT(condition)                                                             \
    do {                                                                                  \
        if (!(condition) && ffxAssertReport(__FILE__, __LINE__, #condition, NULL)) {     \
            FFX_DEBUG_BREAK                                                               \
        }                                                                                 \
    } while (0)
#define FFX_ASSERT_MESSAGE(condition, msg)                                                \
    do {                                                                                  \
        if (!(condition) && ffxAssertReport(__FILE__, __LINE__, #condition, msg)) {      \
            FFX_DEBUG_BREAK                                                               \
        }                                                                                 \
    } while (0)
#define FFX_ASSERT_FAIL(message)                            \
    do {                                                    \
        ffxAssertReport(__FILE__, __LINE__, NULL, message); \
        FFX_DEBUG_BREAK                                     \
    } while (0)
#else
#define FFX_ASSERT(condition) \
    do {                      \
        FFX_UNUSED(condition); \
    } while (0)
#define FFX_ASSERT_MESSAGE(condition, message) \
    do {                                       \
        FFX_UNUSED(condition);                 \
        FFX_UNUSED(message);                   \
    } while (0)
#define FFX_ASSERT_FAIL(message) \
    do {                         \
        FFX_UNUSED(message);     \
    } while (0)
#endif

#ifdef __cplusplus
#define FFX_STATIC_ASSERT(condition) static_assert(condition, #condition)
#else
#define FFX_STATIC_ASSERT(condition) _Static_assert(condition, #condition)
#endif

#ifdef __cplusplus
}
#endif

#endif
