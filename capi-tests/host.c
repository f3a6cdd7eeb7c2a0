#include "host.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void host_fail(const char *file, int line, const char *cond, const char *fmt, ...)
{
    va_list args;
    fflush(stdout);
    fprintf(stderr, "%s:%d: check failed: %s: ", file, line, cond);
    va_start(args, fmt);
    vfprintf(stderr, fmt, args);
    va_end(args);
    fputc('\n', stderr);
    exit(1);
}

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT types,
                                                            const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                            void *user)
{
    Host *h = (Host *)user;
    (void)types;
    h->validationMessages++;
    fprintf(stderr, "validation %s: %s\n", severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "ERROR" : "WARNING",
            data && data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

static bool has_layer(const char *name)
{
    uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, NULL));
    VkLayerProperties *layers = calloc(count ? count : 1, sizeof *layers);
    CHECK(layers != NULL, "out of memory");
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers));
    bool found = false;
    for (uint32_t i = 0; i < count; i++) found = found || strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static bool device_has_extension(VkPhysicalDevice pd, const char *name)
{
    uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(pd, NULL, &count, NULL));
    VkExtensionProperties *exts = calloc(count ? count : 1, sizeof *exts);
    CHECK(exts != NULL, "out of memory");
    VK_CHECK(vkEnumerateDeviceExtensionProperties(pd, NULL, &count, exts));
    bool found = false;
    for (uint32_t i = 0; i < count; i++) found = found || strcmp(exts[i].extensionName, name) == 0;
    free(exts);
    return found;
}

static void create_instance_without_layers(Host *h)
{
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "dnsr-capi-tests",
        .apiVersion = VK_API_VERSION_1_2,
    };
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VK_CHECK(vkCreateInstance(&info, NULL, &h->instance));
}

static void create_instance(Host *h, bool rawHandles)
{
    const char *layer = "VK_LAYER_KHRONOS_validation";
    CHECK(has_layer(layer), "%s is not installed (apt-get install vulkan-validationlayers)", layer);
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};

    VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation_message,
        .pUserData = h,
    };
    /* Chained into the instance create info too, so messages of vkCreateInstance/vkDestroyInstance count. */
    VkValidationFeatureDisableEXT disables[] = {VK_VALIDATION_FEATURE_DISABLE_UNIQUE_HANDLES_EXT};
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
        .disabledValidationFeatureCount = rawHandles ? 1u : 0u,
        .pDisabledValidationFeatures = disables,
    };
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "dnsr-capi-tests",
        .apiVersion = VK_API_VERSION_1_2,
    };
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = &features,
        .pApplicationInfo = &app,
        .enabledLayerCount = 1,
        .ppEnabledLayerNames = &layer,
        .enabledExtensionCount = 1,
        .ppEnabledExtensionNames = extensions,
    };
    VK_CHECK(vkCreateInstance(&info, NULL, &h->instance));
    PFN_vkCreateDebugUtilsMessengerEXT create =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkCreateDebugUtilsMessengerEXT");
    CHECK(create != NULL, "vkCreateDebugUtilsMessengerEXT not available");
    VK_CHECK(create(h->instance, &messenger, NULL, &h->messenger));
    h->setObjectName =
        (PFN_vkSetDebugUtilsObjectNameEXT)vkGetInstanceProcAddr(h->instance, "vkSetDebugUtilsObjectNameEXT");
    h->layers = true;
}

static void pick_device(Host *h)
{
    const char *wanted = getenv("DNSR_DEVICE");
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(h->instance, &count, NULL));
    CHECK(count > 0, "no Vulkan device (install mesa-vulkan-drivers for lavapipe)");
    VkPhysicalDevice *devices = calloc(count, sizeof *devices);
    CHECK(devices != NULL, "out of memory");
    VK_CHECK(vkEnumeratePhysicalDevices(h->instance, &count, devices));
    for (uint32_t i = 0; i < count && h->physicalDevice == VK_NULL_HANDLE; i++) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        if (wanted == NULL || wanted[0] == '\0' || strstr(props.deviceName, wanted) != NULL) {
            h->physicalDevice = devices[i];
            memcpy(h->deviceName, props.deviceName, sizeof h->deviceName);
        }
    }
    free(devices);
    CHECK(h->physicalDevice != VK_NULL_HANDLE, "no Vulkan device name contains DNSR_DEVICE=\"%s\"", wanted);

    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(h->physicalDevice, &families, NULL);
    VkQueueFamilyProperties *props = calloc(families ? families : 1, sizeof *props);
    CHECK(props != NULL, "out of memory");
    vkGetPhysicalDeviceQueueFamilyProperties(h->physicalDevice, &families, props);
    h->queueFamily = UINT32_MAX;
    for (uint32_t i = 0; i < families && h->queueFamily == UINT32_MAX; i++)
        if (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) h->queueFamily = i;
    free(props);
    CHECK(h->queueFamily != UINT32_MAX, "%s has no compute queue", h->deviceName);
}

static void create_device(Host *h, bool allShaderStages)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(h->physicalDevice, &props);
    CHECK(props.apiVersion >= VK_API_VERSION_1_2, "%s supports Vulkan %u.%u; the tests need 1.2", h->deviceName,
          VK_API_VERSION_MAJOR(props.apiVersion), VK_API_VERSION_MINOR(props.apiVersion));
    h->apiVersion = VK_API_VERSION_1_2;

    VkPhysicalDeviceVulkan11Features f11 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, .pNext = &f11};
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12};
    vkGetPhysicalDeviceFeatures2(h->physicalDevice, &f2);

    bool float16 = f12.shaderFloat16 && f11.storageBuffer16BitAccess;
    bool push = device_has_extension(h->physicalDevice, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    h->pipelineStatistics = f2.features.pipelineStatisticsQuery == VK_TRUE;

    VkPhysicalDeviceVulkan11Features e11 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
        .storageBuffer16BitAccess = float16,
    };
    VkPhysicalDeviceVulkan12Features e12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &e11,
        .shaderFloat16 = float16,
    };
    VkPhysicalDeviceFeatures2 e2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &e12};
    e2.features.pipelineStatisticsQuery = h->pipelineStatistics;
    if (allShaderStages) {
        h->geometryShader = f2.features.geometryShader == VK_TRUE;
        h->tessellationShader = f2.features.tessellationShader == VK_TRUE;
        e2.features.geometryShader = f2.features.geometryShader;
        e2.features.tessellationShader = f2.features.tessellationShader;
    }

    const char *extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = h->queueFamily,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &e2,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = push ? 1u : 0u,
        .ppEnabledExtensionNames = extensions,
    };
    VK_CHECK(vkCreateDevice(h->physicalDevice, &info, NULL, &h->device));
    vkGetDeviceQueue(h->device, h->queueFamily, 0, &h->queue);
    h->features = (float16 ? DNSR_FEATURE_FLOAT16 : 0u) | (push ? DNSR_FEATURE_PUSH_DESCRIPTOR : 0u);

    VkCommandPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = h->queueFamily,
    };
    VK_CHECK(vkCreateCommandPool(h->device, &pool, NULL, &h->commandPool));
}

void host_create(Host *h)
{
    host_create_with(h, NULL);
}

void host_create_with(Host *h, const HostOptions *options)
{
    HostOptions defaults;
    memset(&defaults, 0, sizeof defaults);
    const HostOptions *o = options ? options : &defaults;
    memset(h, 0, sizeof *h);
    if (o->noLayers)
        create_instance_without_layers(h);
    else
        create_instance(h, o->rawHandles);
    pick_device(h);
    create_device(h, o->allShaderStages);
    printf("device: %s (features 0x%x, pipeline statistics %s)%s%s%s\n", h->deviceName, h->features,
           h->pipelineStatistics ? "yes" : "no", o->noLayers ? ", no layers" : "",
           o->rawHandles ? ", validation without unique handles" : "",
           o->allShaderStages ? (h->geometryShader && h->tessellationShader ? ", geometry+tessellation on"
                                                                             : ", geometry/tessellation partly off")
                              : "");
    host_expect_clean(h, "host_create");
}

void host_destroy(Host *h)
{
    if (h->device) {
        VK_CHECK(vkDeviceWaitIdle(h->device));
        vkDestroyCommandPool(h->device, h->commandPool, NULL);
        vkDestroyDevice(h->device, NULL);
    }
    if (h->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkDestroyDebugUtilsMessengerEXT");
        destroy(h->instance, h->messenger, NULL);
    }
    if (h->instance) vkDestroyInstance(h->instance, NULL);
    /* Messages of vkDestroyDevice/vkDestroyInstance (e.g. leaked objects) count too. */
    host_expect_clean(h, "host_destroy");
    memset(h, 0, sizeof *h);
}

void host_expect_clean(const Host *h, const char *where)
{
    CHECK(h->validationMessages == 0, "%u validation message(s) by the end of %s (printed above)", h->validationMessages,
          where);
}

DnsrContextCreateInfo host_create_info(const Host *h, uint32_t width, uint32_t height)
{
    DnsrContextCreateInfo info;
    memset(&info, 0, sizeof info);
    info.sType = DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO;
    info.instance = h->instance;
    info.physicalDevice = h->physicalDevice;
    info.device = h->device;
    /* The loader's own entry points: dnsr loads everything else through them (and so through the layers). */
    info.vulkanFunctions.vkGetInstanceProcAddr = vkGetInstanceProcAddr;
    info.vulkanFunctions.vkGetDeviceProcAddr = vkGetDeviceProcAddr;
    info.apiVersion = h->apiVersion;
    info.queueFamilyIndex = h->queueFamily;
    info.enabledFeatures = h->features;
    info.width = width;
    info.height = height;
    info.precision = DNSR_PRECISION_FP32;
    info.outputFormat = VK_FORMAT_R32_SFLOAT;
    info.lightCount = 1;
    return info;
}

uint32_t host_memory_type(const Host *h, uint32_t typeBits, VkMemoryPropertyFlags flags)
{
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(h->physicalDevice, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; i++)
        if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
    host_fail(__FILE__, __LINE__, "memory type", "no memory type in bits 0x%x with flags 0x%x", typeBits, flags);
}

static bool is_depth(VkFormat f)
{
    return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32;
}

static VkImageAspectFlags aspect_of(VkFormat f)
{
    return is_depth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

static uint32_t texel_bytes(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UNORM:
    case VK_FORMAT_D16_UNORM: return 2;
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R16G16_SNORM: return 4;
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT: return 16;
    default: host_fail(__FILE__, __LINE__, "texel_bytes", "no texel size for format %d", (int)f);
    }
}

VkImageMemoryBarrier host_transition(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to)
{
    VkImageMemoryBarrier b = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
        .oldLayout = from,
        .newLayout = to,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = {aspect, 0, 1, 0, 1},
    };
    return b;
}

void host_cmd_full_barrier_with(VkCommandBuffer cmd, const VkImageMemoryBarrier *images, uint32_t count)
{
    VkMemoryBarrier m = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &m, 0, NULL,
                         count, images);
}

void host_cmd_full_barrier(VkCommandBuffer cmd)
{
    host_cmd_full_barrier_with(cmd, NULL, 0);
}

void host_cmd_host_read_barrier(VkCommandBuffer cmd)
{
    VkMemoryBarrier m = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &m, 0, NULL, 0, NULL);
}

void host_image_create(Host *h, HostImage *img, VkFormat format, uint32_t width, uint32_t height, VkImageLayout layout)
{
    memset(img, 0, sizeof *img);
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(h->physicalDevice, format, &fp);
    VkImageUsageFlags usage =
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    if (is_depth(format)) usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = format,
        .extent = {width, height, 1},
        .mipLevels = 1,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = usage,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    VK_CHECK(vkCreateImage(h->device, &info, NULL, &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(h->device, img->image, &req);
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = host_memory_type(h, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
    };
    VK_CHECK(vkAllocateMemory(h->device, &alloc, NULL, &img->memory));
    VK_CHECK(vkBindImageMemory(h->device, img->image, img->memory, 0));
    VkImageViewCreateInfo view = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = img->image,
        .viewType = VK_IMAGE_VIEW_TYPE_2D,
        .format = format,
        .subresourceRange = {aspect_of(format), 0, 1, 0, 1},
    };
    VK_CHECK(vkCreateImageView(h->device, &view, NULL, &img->view));
    img->format = format;
    img->width = width;
    img->height = height;
    img->texelBytes = texel_bytes(format);
    img->layout = layout;

    VkCommandBuffer cmd = host_begin(h);
    VkImageMemoryBarrier b = host_transition(img->image, aspect_of(format), VK_IMAGE_LAYOUT_UNDEFINED, layout);
    host_cmd_full_barrier_with(cmd, &b, 1);
    host_submit(h, cmd);
}

void host_image_destroy(Host *h, HostImage *img)
{
    vkDestroyImageView(h->device, img->view, NULL);
    vkDestroyImage(h->device, img->image, NULL);
    vkFreeMemory(h->device, img->memory, NULL);
    memset(img, 0, sizeof *img);
}

DnsrHostImage host_image_desc(const HostImage *img)
{
    DnsrHostImage d = {img->image, img->view, img->format, img->layout, img->width, img->height};
    return d;
}

void host_dispatch_neutral(DnsrShadowsDispatch *d)
{
    d->motionVectorScale[0] = d->motionVectorScale[1] = 1.0f;
    d->normalsUnpackMul = 1.0f;
    d->normalsUnpackAdd = 0.0f;
    for (int i = 0; i < 16; i++) {
        float v = (i % 5 == 0) ? 1.0f : 0.0f;
        d->projectionInverse[i] = d->reprojectionMatrix[i] = d->viewProjectionInverse[i] = v;
    }
    d->depthSimilaritySigma = 1.0f;
    d->sync.inputSrcStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
    d->sync.inputSrcAccess = VK_ACCESS_TRANSFER_WRITE_BIT;
    d->sync.outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
    d->sync.outputDstAccess = VK_ACCESS_TRANSFER_READ_BIT;
}

DnsrShadowsDispatch host_dispatch(VkCommandBuffer cmd, const HostImage *mask, const HostImage *depth, const HostImage *velocity,
                                  const HostImage *normals, const HostImage *output)
{
    DnsrShadowsDispatch d;
    memset(&d, 0, sizeof d);
    d.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH;
    d.commandBuffer = cmd;
    d.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;
    d.hitMask = host_image_desc(mask);
    d.depth = host_image_desc(depth);
    d.velocity = host_image_desc(velocity);
    d.normals = host_image_desc(normals);
    d.output = host_image_desc(output);
    host_dispatch_neutral(&d);
    return d;
}

size_t host_image_bytes(const HostImage *img)
{
    return (size_t)img->width * img->height * img->texelBytes;
}

void host_buffer_create(Host *h, HostBuffer *b, VkDeviceSize size)
{
    memset(b, 0, sizeof *b);
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size < 4 ? 4 : size,
        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
    };
    VK_CHECK(vkCreateBuffer(h->device, &info, NULL, &b->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(h->device, b->buffer, &req);
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = host_memory_type(h, req.memoryTypeBits,
                                            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT),
    };
    VK_CHECK(vkAllocateMemory(h->device, &alloc, NULL, &b->memory));
    VK_CHECK(vkBindBufferMemory(h->device, b->buffer, b->memory, 0));
    VK_CHECK(vkMapMemory(h->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    b->size = info.size;
}

void host_buffer_destroy(Host *h, HostBuffer *b)
{
    vkDestroyBuffer(h->device, b->buffer, NULL);
    vkFreeMemory(h->device, b->memory, NULL);
    memset(b, 0, sizeof *b);
}

VkCommandBuffer host_begin(Host *h)
{
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = h->commandPool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(h->device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void host_submit(Host *h, VkCommandBuffer cmd)
{
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    VK_CHECK(vkQueueSubmit(h->queue, 1, &submit, VK_NULL_HANDLE));
    VK_CHECK(vkQueueWaitIdle(h->queue));
    vkFreeCommandBuffers(h->device, h->commandPool, 1, &cmd);
}

void host_cmd_copy(VkCommandBuffer cmd, const HostImage *img, const HostBuffer *buf, VkDeviceSize offset, bool toImage)
{
    VkImageAspectFlags aspect = aspect_of(img->format);
    VkImageLayout transfer = toImage ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkBufferImageCopy region = {
        .bufferOffset = offset,
        .imageSubresource = {aspect, 0, 0, 1},
        .imageExtent = {img->width, img->height, 1},
    };
    VkImageMemoryBarrier b = host_transition(img->image, aspect, img->layout, transfer);
    host_cmd_full_barrier_with(cmd, img->layout != transfer ? &b : NULL, img->layout != transfer ? 1u : 0u);
    if (toImage)
        vkCmdCopyBufferToImage(cmd, buf->buffer, img->image, transfer, 1, &region);
    else
        vkCmdCopyImageToBuffer(cmd, img->image, transfer, buf->buffer, 1, &region);
    b = host_transition(img->image, aspect, transfer, img->layout);
    host_cmd_full_barrier_with(cmd, img->layout != transfer ? &b : NULL, img->layout != transfer ? 1u : 0u);
}

void host_upload(Host *h, const HostImage *img, const void *data, size_t bytes)
{
    CHECK(bytes == host_image_bytes(img), "upload of %zu bytes into an image of %zu", bytes, host_image_bytes(img));
    HostBuffer staging;
    host_buffer_create(h, &staging, bytes);
    memcpy(staging.mapped, data, bytes);
    VkCommandBuffer cmd = host_begin(h);
    host_cmd_copy(cmd, img, &staging, 0, true);
    host_submit(h, cmd);
    host_buffer_destroy(h, &staging);
}

void host_download(Host *h, const HostImage *img, void *data, size_t bytes)
{
    CHECK(bytes == host_image_bytes(img), "download of %zu bytes from an image of %zu", bytes, host_image_bytes(img));
    HostBuffer staging;
    host_buffer_create(h, &staging, bytes);
    VkCommandBuffer cmd = host_begin(h);
    host_cmd_copy(cmd, img, &staging, 0, false);
    host_cmd_host_read_barrier(cmd);
    host_submit(h, cmd);
    memcpy(data, staging.mapped, bytes);
    host_buffer_destroy(h, &staging);
}
