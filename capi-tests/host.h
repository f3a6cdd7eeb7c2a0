/*
 * The engine's side of the C API tests: one Vulkan instance with the validation layer (synchronization
 * validation on, every WARNING/ERROR message counted), one device with a compute queue, images with staging
 * upload/readback, and a DnsrContextCreateInfo filled for that device.
 *
 * Every helper fails the test (exit 1, with file:line) instead of returning an error: a test that cannot set up
 * its Vulkan objects has nothing to say about dnsr.
 */
#ifndef DNSR_CAPI_TESTS_HOST_H
#define DNSR_CAPI_TESTS_HOST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#include "dnsr.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Prints "file:line: check failed: <cond>: <message>" and exits with status 1. */
void host_fail(const char *file, int line, const char *cond, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5), noreturn))
#endif
    ;

/* CHECK(cond, "format", args...): fails the test with the formatted message when cond is false. */
#define CHECK(cond, ...)                                                                                        \
    do {                                                                                                        \
        if (!(cond)) host_fail(__FILE__, __LINE__, #cond, __VA_ARGS__);                                        \
    } while (0)

/* VK_CHECK(call): fails the test when a Vulkan call does not return VK_SUCCESS. */
#define VK_CHECK(call)                                                                                          \
    do {                                                                                                        \
        VkResult vk_check_result_ = (call);                                                                     \
        if (vk_check_result_ != VK_SUCCESS) host_fail(__FILE__, __LINE__, #call, "VkResult %d", (int)vk_check_result_); \
    } while (0)

/* DNSR_CHECK(call): fails the test when a dnsr call does not return DNSR_SUCCESS, printing its message. */
#define DNSR_CHECK(call)                                                                                        \
    do {                                                                                                        \
        DnsrResult dnsr_check_result_ = (call);                                                                 \
        if (dnsr_check_result_ != DNSR_SUCCESS)                                                                 \
            host_fail(__FILE__, __LINE__, #call, "%s: %s", dnsr_result_to_string(dnsr_check_result_),          \
                      dnsr_last_error_message());                                                               \
    } while (0)

typedef struct Host {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physicalDevice;
    VkDevice device;
    VkQueue queue;
    uint32_t queueFamily;
    VkCommandPool commandPool;
    /* The apiVersion the instance and device were created with (what dnsr must be told). */
    uint32_t apiVersion;
    /* DNSR_FEATURE_* bits actually enabled on the device. */
    DnsrFeatureFlags features;
    /* pipelineStatisticsQuery is enabled (compute shader invocation counts can prove a command buffer ran no
     * dispatch). */
    bool pipelineStatistics;
    char deviceName[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];
    /* vkSetDebugUtilsObjectNameEXT (VK_EXT_debug_utils is always enabled with the validation layer). */
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName;
    /* WARNING and ERROR messages the validation layer sent so far. */
    unsigned validationMessages;
    /* The validation layer is loaded (false after host_create_with(.noLayers = true)). */
    bool layers;
    /* geometryShader / tessellationShader are enabled (only with HostOptions.allShaderStages). */
    bool geometryShader;
    bool tessellationShader;
} Host;

/* What host_create_with changes from host_create's defaults (all false = host_create). */
typedef struct HostOptions {
    /* No layer at all: the application sees the driver's own handles, as a shipping engine does. */
    bool noLayers;
    /* The validation layer without its unique-handle wrapping (VK_VALIDATION_FEATURE_DISABLE_UNIQUE_HANDLES_EXT):
     * the application and the layer see the driver's handle values, so a value the driver reuses for a new
     * object is the same value the layer tracks. */
    bool rawHandles;
    /* Also enable geometryShader and tessellationShader where the device has them, so that every pipeline stage
     * the device supports is legal in a barrier. */
    bool allShaderStages;
} HostOptions;

/* A 2D image with its memory and view, resting in `layout` between uses. */
typedef struct HostImage {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
    VkFormat format;
    uint32_t width;
    uint32_t height;
    uint32_t texelBytes;
    VkImageLayout layout;
} HostImage;

/* A host-visible, coherent, persistently mapped buffer. */
typedef struct HostBuffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
    VkDeviceSize size;
} HostBuffer;

/* Creates instance (validation layer + synchronization validation + messenger; fails if the layer is missing),
 * picks the device whose name contains $DNSR_DEVICE (default: the first), creates a device with a compute queue
 * and every optional feature dnsr can use that the device has, plus pipelineStatisticsQuery when available. */
void host_create(Host *h);
/* host_create with options (NULL = host_create). */
void host_create_with(Host *h, const HostOptions *options);
/* Destroys everything host_create made; fails if the validation layer reported anything (leaks included). */
void host_destroy(Host *h);
/* Fails the test if any validation message arrived (`where` names the step). */
void host_expect_clean(const Host *h, const char *where);

/* A create info for this device with its enabled features: FP32, R32_SFLOAT output, one light. */
DnsrContextCreateInfo host_create_info(const Host *h, uint32_t width, uint32_t height);

uint32_t host_memory_type(const Host *h, uint32_t typeBits, VkMemoryPropertyFlags flags);

/* A 2D image usable as sampled, storage (when the format supports it) and transfer source/destination, moved
 * from UNDEFINED to `layout` before this returns. */
void host_image_create(Host *h, HostImage *img, VkFormat format, uint32_t width, uint32_t height, VkImageLayout layout);
void host_image_destroy(Host *h, HostImage *img);
/* The image as dnsr sees it: its view, format, resting layout and extent. */
DnsrHostImage host_image_desc(const HostImage *img);
size_t host_image_bytes(const HostImage *img);
/* The scene-independent fields of a dispatch the tests share: unit motion-vector scale, normals stored as-is,
 * identity matrices, depth sigma 1, inputs written and output read by transfers. */
void host_dispatch_neutral(DnsrShadowsDispatch *d);
/* A dispatch of five host images (an OCCLUDED_BITS hit mask) into `cmd`, with host_dispatch_neutral's constants. */
DnsrShadowsDispatch host_dispatch(VkCommandBuffer cmd, const HostImage *mask, const HostImage *depth, const HostImage *velocity,
                                  const HostImage *normals, const HostImage *output);

void host_buffer_create(Host *h, HostBuffer *b, VkDeviceSize size);
void host_buffer_destroy(Host *h, HostBuffer *b);

/* Allocates and begins a one-time command buffer. */
VkCommandBuffer host_begin(Host *h);
/* Ends, submits and waits for a command buffer from host_begin, then frees it. */
void host_submit(Host *h, VkCommandBuffer cmd);
/* An all-commands, all-memory barrier (test plumbing only). */
void host_cmd_full_barrier(VkCommandBuffer cmd);
/* The same, carrying image layout transitions. */
void host_cmd_full_barrier_with(VkCommandBuffer cmd, const VkImageMemoryBarrier *images, uint32_t count);
/* A layout transition of mip 0 / layer 0 (all memory accesses before -> all after). */
VkImageMemoryBarrier host_transition(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to);
/* Makes transfer writes (readback copies) visible to the host once the queue is idle. */
void host_cmd_host_read_barrier(VkCommandBuffer cmd);
/* Copies between an image and a buffer at `offset`, moving the image to the transfer layout and back to its
 * resting layout with full barriers around the copy. */
void host_cmd_copy(VkCommandBuffer cmd, const HostImage *img, const HostBuffer *buf, VkDeviceSize offset, bool toImage);

/* Uploads `bytes` texels (tightly packed) into an image and waits. */
void host_upload(Host *h, const HostImage *img, const void *data, size_t bytes);
/* Reads the image back (tightly packed) and waits. */
void host_download(Host *h, const HostImage *img, void *data, size_t bytes);

#ifdef __cplusplus
}
#endif

#endif
