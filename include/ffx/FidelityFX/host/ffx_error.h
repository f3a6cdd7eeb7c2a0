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

/* The result of every FFX function that can fail: FFX_OK or one of the FfxErrorCodes values. As in the SDK, the
 * codes are written from 0x80000000 up, which makes FfxErrorCodes' underlying type unsigned (C++; GCC and Clang in
 * C): stored in an FfxErrorCode they are negative, but `code < FFX_OK` compares as unsigned and is false. Test for
 * `code != FFX_OK`. */
typedef int32_t FfxErrorCode;

typedef enum FfxErrorCodes {
    FFX_OK = 0,
    FFX_ERROR_INVALID_POINTER = 0x80000000,
    FFX_ERROR_INVALID_ALIGNMENT = 0x80000001,
    FFX_ERROR_INVALID_SIZE = 0x80000002,
    FFX_EOF = 0x80000003,
    FFX_ERROR_INVALID_PATH = 0x80000004,
    FFX_ERROR_EOF = 0x80000005,
    FFX_ERROR_MALFORMED_DATA = 0x80000006,
    FFX_ERROR_OUT_OF_MEMORY = 0x80000007,
    FFX_ERROR_INCOMPLETE_INTERFACE = 0x80000008,
    FFX_ERROR_INVALID_ENUM = 0x80000009,
    FFX_ERROR_INVALID_ARGUMENT = 0x8000000a,
    FFX_ERROR_OUT_OF_RANGE = 0x8000000b,
    FFX_ERROR_NULL_DEVICE = 0x8000000c,
    FFX_ERROR_BACKEND_API_ERROR = 0x8000000d,
    FFX_ERROR_INSUFFICIENT_MEMORY = 0x8000000e,
    FFX_ERROR_INVALID_VERSION = 0x8000000f,
    FFX_ERROR_ACCESS_DENIED = 0x80000010
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
