/*
 * ffx_glue: the glue code of an SDK 1.1.4 shadow-denoiser integration compiles and links against dnsr's
 * include/ffx and libdnsr alone: the utility, assert and message headers (ffx_interface.h in the SDK pulls them
 * in), their macros (FFX_ASSERT, FFX_UNUSED, FFX_ARRAY_ELEMENTS, FFX_CONTAINS_FLAG, ...), the message and assert
 * callbacks, and the Vulkan getters ffxGetBufferResourceDescriptionVK, ffxGetCommandQueueVK and ffxGetPipelineVK.
 * The message callback receives the error of a refused FFX call. No device is needed.
 */
#define _DEBUG 1
#include <FidelityFX/host/backends/vk/ffx_vk.h>
#include <FidelityFX/host/ffx_assert.h>
#include <FidelityFX/host/ffx_denoiser.h>
#include <FidelityFX/host/ffx_interface.h>
#include <FidelityFX/host/ffx_message.h>
#include <FidelityFX/host/ffx_util.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cwchar>
#include <string>

static int failures = 0;
#define EXPECT(cond, ...)                                        \
    do {                                                         \
        if (!(cond)) {                                           \
            std::printf("ffx_glue: %s: ", #cond);                \
            std::printf(__VA_ARGS__);                            \
            std::printf("\n");                                   \
            failures++;                                          \
        }                                                        \
    } while (0)

static std::wstring lastMessage;
static uint32_t lastType = 99;
static void onMessage(uint32_t type, const wchar_t *message)
{
    lastType = type;
    lastMessage = message;
}
static std::string lastAssert;
static void onAssert(const char *message) { lastAssert = message; }

FFX_STATIC_ASSERT(FFX_MAKE_VERSION(1, 1, 4) == FFX_SDK_MAKE_VERSION(1, 1, 4));

int main(void)
{
    int unused = 3;
    FFX_UNUSED(unused);
    const uint32_t table[7] = {};
    EXPECT(FFX_ARRAY_ELEMENTS(table) == 7, "%d", FFX_ARRAY_ELEMENTS(table));
    EXPECT(FFX_CONTAINS_FLAG(FFX_RESOURCE_USAGE_UAV | FFX_RESOURCE_USAGE_DEPTHTARGET, FFX_RESOURCE_USAGE_UAV), "contains");
    EXPECT(!FFX_CONTAINS_FLAG(FFX_RESOURCE_USAGE_UAV, FFX_RESOURCE_USAGE_UAV | FFX_RESOURCE_USAGE_DEPTHTARGET), "contains");
    EXPECT(FFX_ALIGN_UP(13u, 8u) == 16u && FFX_DIVIDE_ROUNDING_UP(13u, 8u) == 2u, "align");
    EXPECT(FFX_MAXIMUM(2, 5) == 5 && FFX_MINIMUM(2, 5) == 2 && FFX_ABSOLUTE(-4) == 4 && FFX_SIGN(-4) == -1, "min/max");
    EXPECT(std::strcmp(FFX_STR(FFX_MAXIMUM_PATH), "(260)") == 0, "%s", FFX_STR(FFX_MAXIMUM_PATH));

    // The backend limits glue code sizes its tables by, and the resource init description (SDK 1.1.4's values).
    FfxUInt32 srvs[FFX_MAX_NUM_SRVS + FFX_MAX_NUM_UAVS + FFX_MAX_NUM_CONST_BUFFERS] = {};
    EXPECT(FFX_ARRAY_ELEMENTS(srvs) == 131, "%d", FFX_ARRAY_ELEMENTS(srvs));
    EXPECT(FFX_MAX_RESOURCE_COUNT == 512 && FFX_MAX_PASS_COUNT == 50 && FFX_MAX_BARRIERS == 128 && FFX_MAX_GPU_JOBS == 256 &&
               FFX_MAX_SAMPLERS == 16 && FFX_RING_BUFFER_DESCRIPTOR_COUNT == 4 * 50 * 512 &&
               FFX_CONSTANT_BUFFER_RING_BUFFER_SIZE == 4 * 50 * 4096,
           "limits");
    unsigned char bytes[16] = {};
    FfxResourceInitData byValue = FfxResourceInitData::FfxResourceInitValue(64, 0x7f);
    FfxResourceInitData byBuffer = FfxResourceInitData::FfxResourceInitBuffer(sizeof bytes, bytes);
    EXPECT(byValue.type == FFX_RESOURCE_INIT_DATA_TYPE_VALUE && byValue.size == 64 && byValue.value == 0x7f, "init value");
    EXPECT(byBuffer.type == FFX_RESOURCE_INIT_DATA_TYPE_BUFFER && byBuffer.size == 16 && byBuffer.buffer == bytes, "init buffer");
    static_assert(sizeof(FfxResourceInitData) == 3 * sizeof(void *), "FfxResourceInitData's size");
    static_assert(offsetof(FfxResourceInitData, buffer) == 2 * sizeof(void *), "FfxResourceInitData::buffer's offset");
    static_assert(FFX_RESOURCE_INIT_DATA_TYPE_VALUE == 3, "FfxResourceInitDataType");

    // Asserts (_DEBUG): a failed one reports through the callback; a passing one does not.
    ffxAssertSetPrintingCallback(onAssert);
    FFX_ASSERT(unused == 3);
    EXPECT(lastAssert.empty(), "a passing assert reported %s", lastAssert.c_str());
    FFX_ASSERT_MESSAGE(unused == 4, "unused is 3");
    EXPECT(lastAssert.find("unused == 4") != std::string::npos && lastAssert.find("unused is 3") != std::string::npos,
           "report: %s", lastAssert.c_str());
    ffxAssertSetPrintingCallback(nullptr);

    // Messages: a refused FFX call's error reaches the callback.
    ffxSetPrintMessageCallback(onMessage, 0);
    ffxPrintMessage(FFX_MESSAGE_TYPE_WARNING, L"hello");
    EXPECT(lastType == FFX_MESSAGE_TYPE_WARNING && lastMessage == L"hello", "ffxPrintMessage");
    FfxDenoiserContextDescription desc = {};
    FfxErrorCode code = ffxDenoiserContextCreate(nullptr, &desc);
    EXPECT(code == FfxErrorCode(FFX_ERROR_INVALID_POINTER), "code 0x%08x", unsigned(code));
    EXPECT(lastType == FFX_MESSAGE_TYPE_ERROR && lastMessage.find(L"pContext") != std::wstring::npos, "message %ls",
           lastMessage.c_str());
    ffxSetPrintMessageCallback(nullptr, 0);

    // The Vulkan getters.
    VkBufferCreateInfo bufferInfo = {};
    bufferInfo.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bufferInfo.size = 4096;
    bufferInfo.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    VkBuffer buffer = reinterpret_cast<VkBuffer>(uintptr_t(0x1234));
    FfxResourceDescription b = ffxGetBufferResourceDescriptionVK(buffer, bufferInfo);
    EXPECT(b.type == FFX_RESOURCE_TYPE_BUFFER && b.size == 4096 && b.stride == 0 && b.format == FFX_SURFACE_FORMAT_UNKNOWN,
           "buffer %d %u %u %d", int(b.type), b.size, b.stride, int(b.format));
    EXPECT(b.usage == (FFX_RESOURCE_USAGE_UAV | FFX_RESOURCE_USAGE_INDIRECT), "usage %d", int(b.usage));
    FfxResourceDescription none = ffxGetBufferResourceDescriptionVK(VK_NULL_HANDLE, bufferInfo, FFX_RESOURCE_USAGE_UAV);
    EXPECT(none.size == 0 && none.usage == 0, "a null buffer");
    VkQueue queue = reinterpret_cast<VkQueue>(uintptr_t(0x5678));
    VkPipeline pipeline = reinterpret_cast<VkPipeline>(uintptr_t(0x9abc));
    EXPECT(ffxGetCommandQueueVK(queue) == static_cast<FfxCommandQueue>(queue), "queue");
    EXPECT(ffxGetPipelineVK(pipeline) == reinterpret_cast<FfxPipeline>(pipeline), "pipeline");

    if (failures) return 1;
    std::printf("ffx_glue: utility, assert and message headers, their callbacks and the three Vulkan getters work\n");
    return 0;
}
