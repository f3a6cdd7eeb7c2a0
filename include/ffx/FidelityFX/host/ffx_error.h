/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: error codes.
 *
 * Written for dnsr from the SDK's interface (names and values only); see ffx_denoiser.h for what dnsr implements.
 * Every dnsr implementation of an FFX function also sets dnsr_last_error_message() (include <dnsr.h>), which says
 * in words which argument was wrong, where the SDK returns a bare code.
 */
#ifndef FFX_ERROR_H
#define FFX_ERROR_H

#include <stdint.h>

/* The result of every FFX function that can fail: FFX_OK or one of the negative FfxErrorCodes values. */
typedef int32_t FfxErrorCode;

typedef enum FfxErrorCodes {
    FFX_OK = 0,
    FFX_ERROR_INVALID_POINTER = (int32_t)0x80000000,
    FFX_ERROR_INVALID_ALIGNMENT = (int32_t)0x80000001,
    FFX_ERROR_INVALID_SIZE = (int32_t)0x80000002,
    FFX_EOF = (int32_t)0x80000003,
    FFX_ERROR_INVALID_PATH = (int32_t)0x80000004,
    FFX_ERROR_EOF = (int32_t)0x80000005,
    FFX_ERROR_MALFORMED_DATA = (int32_t)0x80000006,
    FFX_ERROR_OUT_OF_MEMORY = (int32_t)0x80000007,
    FFX_ERROR_INCOMPLETE_INTERFACE = (int32_t)0x80000008,
    FFX_ERROR_INVALID_ENUM = (int32_t)0x80000009,
    FFX_ERROR_INVALID_ARGUMENT = (int32_t)0x8000000a,
    FFX_ERROR_OUT_OF_RANGE = (int32_t)0x8000000b,
    FFX_ERROR_NULL_DEVICE = (int32_t)0x8000000c,
    FFX_ERROR_BACKEND_API_ERROR = (int32_t)0x8000000d,
    FFX_ERROR_INSUFFICIENT_MEMORY = (int32_t)0x8000000e,
    FFX_ERROR_INVALID_VERSION = (int32_t)0x8000000f,
    FFX_ERROR_ACCESS_DENIED = (int32_t)0x80000010
} FfxErrorCodes;

/* Returns `error` from the enclosing function when `condition` is false. */
#define FFX_RETURN_ON_ERROR(condition, error) \
    if (!(condition)) {                     \
        return (error);                     \
    }

/* Evaluates `call` and returns its code from the enclosing function unless it is FFX_OK. */
#define FFX_VALIDATE(call)                  \
    {                                       \
        FfxErrorCode ret = (call);          \
        FFX_RETURN_ON_ERROR(ret == FFX_OK, ret); \
    }

#endif
