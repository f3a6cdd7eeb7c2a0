/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the message callback.
 *
 * Written for dnsr from the SDK's interface. libdnsr's FFX functions send every error they return to the callback
 * (FFX_MESSAGE_TYPE_ERROR, the text dnsr_last_error_message() also gives), so an integration that routed the
 * SDK's messages to its log gets dnsr's there too.
 */
#ifndef FFX_MESSAGE_H
#define FFX_MESSAGE_H

#include <stdint.h>
#include <wchar.h>

#include "ffx_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Routes messages to `callback` (NULL: none are printed, as the SDK does outside Windows); debugLevel is kept for
 * the SDK's signature and not used. */
FFX_API void ffxSetPrintMessageCallback(ffxMessageCallback callback, uint32_t debugLevel);
/* Sends `message` (of an FfxMsgType) to the callback, if one is set. */
FFX_API void ffxPrintMessage(uint32_t type, const wchar_t *message);

#ifdef __cplusplus
}
#endif

#endif
