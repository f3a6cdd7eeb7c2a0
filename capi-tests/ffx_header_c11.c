/*
 * ffx_header_c11: dnsr's FidelityFX compatibility headers (the utility, assert and message ones too) compile as
 * C11 (the SDK's own are C++ only) with the SDK's layout, and the version query links and answers 1.3.0.
 */
#include <FidelityFX/host/backends/vk/ffx_vk.h>
#include <FidelityFX/host/ffx_assert.h>
#include <FidelityFX/host/ffx_denoiser.h>
#include <FidelityFX/host/ffx_message.h>
#include <FidelityFX/host/ffx_util.h>

#include <stddef.h>
#include <stdio.h>

_Static_assert(sizeof(FfxResource) == 304, "FfxResource");
static const int k_table[5] = {0};
FFX_STATIC_ASSERT(FFX_ARRAY_ELEMENTS(k_table) == 5 && FFX_CONTAINS_FLAG(6, 2));
_Static_assert(sizeof(FfxInterface) == 232, "FfxInterface");
_Static_assert(sizeof(FfxDenoiserContextDescription) == 248, "FfxDenoiserContextDescription");
_Static_assert(sizeof(FfxDenoiserShadowsDispatchDescription) == 1760, "FfxDenoiserShadowsDispatchDescription");
_Static_assert(offsetof(FfxDenoiserShadowsDispatchDescription, depthSimilaritySigma) == 1752, "depthSimilaritySigma");

int main(void)
{
    FfxVersionNumber v = ffxDenoiserGetEffectVersion();
    if (v != FFX_SDK_MAKE_VERSION(1, 3, 0)) {
        printf("ffxDenoiserGetEffectVersion() = 0x%x, want 0x403000\n", (unsigned)v);
        return 1;
    }
    printf("ffx_header_c11: headers compile as C11; denoiser version 1.3.0\n");
    return 0;
}
