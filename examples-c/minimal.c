/*
 * minimal.c: the smallest complete dnsr integration, in C.
 *
 * What an engine does, in order:
 *   1. create its Vulkan instance and device, enabling what dnsr can use (dnsr_get_device_requirements);
 *   2. create one dnsr context for its render size;
 *   3. every frame, once its shadow rays have written the 1-sample-per-pixel hit mask, record
 *      dnsr_shadows_record into the command buffer it is recording anyway (dnsr never submits or waits);
 *   4. destroy the context before the device.
 *
 * Here the "engine" uploads a synthetic G-buffer (a flat surface facing the camera, nothing moving) and draws
 * each frame's hit mask at random from a known, smooth visibility field, so the denoised output can be compared
 * with the truth. Its "rays" also report how far away their occluder is, which lets dnsr keep the filter within
 * the penumbra (penumbra guidance, DNSR_DISPATCH_USE_HIT_DISTANCE).
 *
 *   cmake -S examples-c -B build/examples -DDNSR_LIB=$PWD/target/release/libdnsr.so
 *   cmake --build build/examples && build/examples/dnsr_minimal [--validate]
 *
 * --validate turns on the Vulkan validation layer (with synchronization validation); any message fails the run.
 */
#include <dnsr.h>
#include <vulkan/vulkan.h>

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WIDTH 64u
#define HEIGHT 48u
#define TILES_X ((WIDTH + 7u) / 8u) /* the hit mask has one uint32 per 8x4-pixel tile */
#define TILES_Y ((HEIGHT + 3u) / 4u)
#define FRAMES 16u
#define LIGHT_ANGULAR_SIZE 0.1f /* radians: the light's angular diameter seen from the surface */

/* Reports a failed Vulkan call and makes the enclosing function return false. */
#define VK_TRY(call)                                                                                              \
    do {                                                                                                          \
        VkResult vk_try_ = (call);                                                                                \
        if (vk_try_ != VK_SUCCESS) {                                                                              \
            fprintf(stderr, "%s failed: VkResult %d\n", #call, (int)vk_try_);                                     \
            return false;                                                                                         \
        }                                                                                                         \
    } while (0)

/* Reports a failed dnsr call with dnsr's own explanation (which field, and why) and returns false. */
#define DNSR_TRY(call)                                                                                            \
    do {                                                                                                          \
        DnsrResult dnsr_try_ = (call);                                                                            \
        if (dnsr_try_ != DNSR_SUCCESS) {                                                                          \
            fprintf(stderr, "%s failed: %s: %s\n", #call, dnsr_result_to_string(dnsr_try_),                     \
                    dnsr_last_error_message());                                                                   \
            return false;                                                                                         \
        }                                                                                                         \
    } while (0)

typedef struct Image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
    VkFormat format;
    uint32_t width, height;
} Image;

/* Host-visible memory every upload and readback goes through; the copies use these fields' offsets. */
typedef struct Staging {
    uint32_t mask[TILES_Y][TILES_X];
    float depth[HEIGHT][WIDTH];
    float hitDistance[HEIGHT][WIDTH];
    uint8_t normals[HEIGHT][WIDTH][4];
    float output[HEIGHT][WIDTH];
} Staging;

typedef struct App {
    bool validate;
    unsigned validationMessages;
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physicalDevice;
    char deviceName[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];
    uint32_t queueFamily;
    VkDevice device;
    VkQueue queue;
    VkCommandPool commandPool;
    VkCommandBuffer cmd;
    DnsrFeatureFlags dnsrFeatures; /* the optional features we enabled, as dnsr must be told */
    DnsrContext denoiser;
    Image mask, depth, velocity, normals, hitDistance, output;
    VkBuffer stagingBuffer;
    VkDeviceMemory stagingMemory;
    Staging *staging;
} App;

/* ------------------------------------------------------------------------------------------------------------- */
/* The synthetic scene                                                                                           */
/* ------------------------------------------------------------------------------------------------------------- */

/* Half-width in pixels of the penumbra at column x: from 2 px on the left to 16 px on the right, as behind an
 * occluder that rises away from the surface. */
static float penumbra(uint32_t x) { return 2.0f + 14.0f * (float)x / WIDTH; }

/* How far above the surface that occluder is: a light of angular diameter a casts a penumbra of half-width
 * distance * tan(a / 2), and one pixel is 2 / HEIGHT view units tall (identity projection). */
static float occluder_distance(uint32_t x)
{
    return penumbra(x) * (2.0f / HEIGHT) / tanf(0.5f * LIGHT_ANGULAR_SIZE);
}

/* True visibility (1 = lit): a slanted shadow edge with that penumbra. */
static float visibility(uint32_t x, uint32_t y)
{
    float across = ((float)y - 0.5f * HEIGHT) + 0.3f * ((float)x - 0.5f * WIDTH);
    float t = 0.5f + 0.5f * across / penumbra(x);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    return t * t * (3.0f - 2.0f * t);
}

/* A deterministic random number in [0, 1) per pixel and frame (an integer hash; any decent one will do). */
static float random01(uint32_t x, uint32_t y, uint32_t frame)
{
    uint32_t h = (x * 0x8da6b343u) ^ (y * 0xd8163841u) ^ (frame * 0xcb1ab31fu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

/* One frame of shadow rays, one per pixel, packed the FidelityFX way: pixel (x, y) is bit (y % 4) * 8 + x % 8
 * of tile (x / 8, y / 4), set when the ray hit an occluder (DNSR_HIT_MASK_OCCLUDED_BITS). */
static void trace_shadow_rays(uint32_t mask[TILES_Y][TILES_X], uint32_t frame)
{
    memset(mask, 0, sizeof(uint32_t) * TILES_X * TILES_Y);
    for (uint32_t y = 0; y < HEIGHT; y++)
        for (uint32_t x = 0; x < WIDTH; x++)
            if (random01(x, y, frame) >= visibility(x, y)) mask[y / 4][x / 8] |= 1u << ((y % 4) * 8 + x % 8);
}

static bool is_lit(uint32_t mask[TILES_Y][TILES_X], uint32_t x, uint32_t y)
{
    return (mask[y / 4][x / 8] & (1u << ((y % 4) * 8 + x % 8))) == 0;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Instance and device: what any engine already has, plus what dnsr asks for                                    */
/* ------------------------------------------------------------------------------------------------------------- */

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT types,
                                                            const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                            void *user)
{
    (void)severity, (void)types;
    ((App *)user)->validationMessages++;
    fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

static bool create_instance(App *app)
{
    VkApplicationInfo appInfo = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "dnsr-minimal",
        .apiVersion = VK_API_VERSION_1_2,
    };
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &appInfo};

    /* Optional: the validation layer with synchronization validation, reporting warnings and errors. */
    const char *layer = "VK_LAYER_KHRONOS_validation";
    const char *debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = &sync,
    };
    VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
        .pfnUserCallback = on_validation_message,
        .pUserData = app,
    };
    if (app->validate) {
        info.pNext = &features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &layer;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &debugUtils;
    }
    VK_TRY(vkCreateInstance(&info, NULL, &app->instance));
    if (app->validate) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(app->instance, "vkCreateDebugUtilsMessengerEXT");
        VK_TRY(create(app->instance, &messenger, NULL, &app->messenger));
    }
    return true;
}

/* The first device with a compute queue, or the first whose name contains $DNSR_DEVICE. */
static bool pick_device(App *app)
{
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    VkResult r = vkEnumeratePhysicalDevices(app->instance, &count, devices);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) {
        fprintf(stderr, "vkEnumeratePhysicalDevices failed: VkResult %d\n", (int)r);
        return false;
    }
    const char *wanted = getenv("DNSR_DEVICE");
    for (uint32_t i = 0; i < count && !app->physicalDevice; i++) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        if (props.apiVersion < VK_API_VERSION_1_2) continue; /* this example enables 1.2 features */
        if (wanted && !strstr(props.deviceName, wanted)) continue;
        VkQueueFamilyProperties families[16];
        uint32_t familyCount = 16;
        vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &familyCount, families);
        for (uint32_t f = 0; f < familyCount && !app->physicalDevice; f++) {
            if (families[f].queueFlags & VK_QUEUE_COMPUTE_BIT) {
                app->physicalDevice = devices[i];
                app->queueFamily = f;
                memcpy(app->deviceName, props.deviceName, sizeof app->deviceName);
            }
        }
    }
    if (!app->physicalDevice) fprintf(stderr, "no Vulkan 1.2 device with a compute queue%s%s\n",
                                      wanted ? " whose name contains " : "", wanted ? wanted : "");
    return app->physicalDevice != VK_NULL_HANDLE;
}

static bool device_has_extension(VkPhysicalDevice physicalDevice, const char *name)
{
    VkExtensionProperties props[512];
    uint32_t count = 512;
    vkEnumerateDeviceExtensionProperties(physicalDevice, NULL, &count, props);
    for (uint32_t i = 0; i < count; i++)
        if (strcmp(props[i].extensionName, name) == 0) return true;
    return false;
}

/* Creates the device with every extension and feature dnsr requires, plus the optional ones the device has. */
static bool create_device(App *app)
{
    DnsrDeviceRequirements req = {.sType = DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS};
    DNSR_TRY(dnsr_get_device_requirements(&req));

    const char *extensions[16];
    uint32_t extensionCount = 0;
    for (uint32_t i = 0; i < req.requiredExtensionCount && extensionCount < 16; i++) {
        if (!device_has_extension(app->physicalDevice, req.ppRequiredExtensionNames[i])) {
            fprintf(stderr, "%s lacks %s, which dnsr requires\n", app->deviceName, req.ppRequiredExtensionNames[i]);
            return false;
        }
        extensions[extensionCount++] = req.ppRequiredExtensionNames[i];
    }
    for (uint32_t i = 0; i < req.optionalExtensionCount && extensionCount < 16; i++) {
        const char *name = req.ppOptionalExtensionNames[i];
        if (!device_has_extension(app->physicalDevice, name)) continue;
        extensions[extensionCount++] = name;
        /* dnsr only uses what it is told about: declare the extension as its feature bit. */
        if (strcmp(name, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) == 0) app->dnsrFeatures |= DNSR_FEATURE_PUSH_DESCRIPTOR;
    }

    /* 16-bit float math is optional: it lets a context use DNSR_PRECISION_FP16. */
    VkPhysicalDeviceVulkan11Features has11 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features has12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &has11,
    };
    VkPhysicalDeviceFeatures2 has = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &has12};
    vkGetPhysicalDeviceFeatures2(app->physicalDevice, &has);
    bool float16 =
        (req.optionalFeatures & DNSR_FEATURE_FLOAT16) && has12.shaderFloat16 && has11.storageBuffer16BitAccess;
    if (float16) app->dnsrFeatures |= DNSR_FEATURE_FLOAT16;
    VkPhysicalDeviceVulkan11Features enable11 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
        .storageBuffer16BitAccess = float16,
    };
    VkPhysicalDeviceVulkan12Features enable12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &enable11,
        .shaderFloat16 = float16,
    };

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = app->queueFamily,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &enable12,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = extensionCount,
        .ppEnabledExtensionNames = extensions,
    };
    VK_TRY(vkCreateDevice(app->physicalDevice, &info, NULL, &app->device));
    vkGetDeviceQueue(app->device, app->queueFamily, 0, &app->queue);

    VkCommandPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, /* one command buffer, re-recorded per frame */
        .queueFamilyIndex = app->queueFamily,
    };
    VK_TRY(vkCreateCommandPool(app->device, &pool, NULL, &app->commandPool));
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = app->commandPool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VK_TRY(vkAllocateCommandBuffers(app->device, &alloc, &app->cmd));
    return true;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* The denoiser                                                                                                  */
/* ------------------------------------------------------------------------------------------------------------- */

static bool create_denoiser(App *app)
{
    /* A header built for another library version would misread every struct: check before anything else. */
    if (dnsr_version() != DNSR_VERSION) {
        fprintf(stderr, "dnsr.h is version 0x%x but libdnsr is 0x%x\n", DNSR_VERSION, dnsr_version());
        return false;
    }
    DnsrContextCreateInfo info = {
        .sType = DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO,
        .instance = app->instance,
        .physicalDevice = app->physicalDevice,
        .device = app->device,
        /* dnsr loads every Vulkan function through these and never links the loader itself. */
        .vulkanFunctions = {vkGetInstanceProcAddr, vkGetDeviceProcAddr},
        .apiVersion = VK_API_VERSION_1_2, /* what the instance and device were created with */
        .queueFamilyIndex = app->queueFamily,
        .enabledFeatures = app->dnsrFeatures,
        .width = WIDTH,
        .height = HEIGHT,
        .precision = DNSR_PRECISION_FP32,
        .outputFormat = VK_FORMAT_R32_SFLOAT, /* R16_SFLOAT and R8_UNORM work too */
        .lightCount = 1,
        /* pSettings NULL: dnsr's defaults (the Quality preset). */
    };
    DNSR_TRY(dnsr_context_create(&info, &app->denoiser));
    return true;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Images and the staging buffer                                                                                 */
/* ------------------------------------------------------------------------------------------------------------- */

static bool memory_type(App *app, uint32_t typeBits, VkMemoryPropertyFlags flags, uint32_t *index)
{
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(app->physicalDevice, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; i++) {
        if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) {
            *index = i;
            return true;
        }
    }
    fprintf(stderr, "no memory type with flags 0x%x\n", flags);
    return false;
}

static bool create_image(App *app, Image *img, VkFormat format, uint32_t width, uint32_t height,
                         VkImageUsageFlags usage)
{
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
    };
    VK_TRY(vkCreateImage(app->device, &info, NULL, &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(app->device, img->image, &req);
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size};
    VkMemoryPropertyFlags deviceLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    if (!memory_type(app, req.memoryTypeBits, deviceLocal, &alloc.memoryTypeIndex)) return false;
    VK_TRY(vkAllocateMemory(app->device, &alloc, NULL, &img->memory));
    VK_TRY(vkBindImageMemory(app->device, img->image, img->memory, 0));
    VkImageViewCreateInfo view = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = img->image,
        .viewType = VK_IMAGE_VIEW_TYPE_2D,
        .format = format,
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
    };
    VK_TRY(vkCreateImageView(app->device, &view, NULL, &img->view));
    img->format = format;
    img->width = width;
    img->height = height;
    return true;
}

/* The engine's images: hit mask, G-buffer (depth, motion vectors, normals), hit distance and the denoised shadow. */
static bool create_images(App *app)
{
    VkImageUsageFlags input = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImageUsageFlags output = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (!create_image(app, &app->mask, VK_FORMAT_R32_UINT, TILES_X, TILES_Y, input) ||
        !create_image(app, &app->depth, VK_FORMAT_R32_SFLOAT, WIDTH, HEIGHT, input) ||
        !create_image(app, &app->velocity, VK_FORMAT_R16G16_SFLOAT, WIDTH, HEIGHT, input) ||
        !create_image(app, &app->normals, VK_FORMAT_R8G8B8A8_UNORM, WIDTH, HEIGHT, input) ||
        !create_image(app, &app->hitDistance, VK_FORMAT_R32_SFLOAT, WIDTH, HEIGHT, input) ||
        !create_image(app, &app->output, VK_FORMAT_R32_SFLOAT, WIDTH, HEIGHT, output))
        return false;

    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = sizeof(Staging),
        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
    };
    VK_TRY(vkCreateBuffer(app->device, &info, NULL, &app->stagingBuffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(app->device, app->stagingBuffer, &req);
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size};
    VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (!memory_type(app, req.memoryTypeBits, host, &alloc.memoryTypeIndex)) return false;
    VK_TRY(vkAllocateMemory(app->device, &alloc, NULL, &app->stagingMemory));
    VK_TRY(vkBindBufferMemory(app->device, app->stagingBuffer, app->stagingMemory, 0));
    VK_TRY(vkMapMemory(app->device, app->stagingMemory, 0, VK_WHOLE_SIZE, 0, (void **)&app->staging));
    return true;
}

static void copy_to_image(App *app, VkDeviceSize offset, const Image *img)
{
    VkBufferImageCopy region = {
        .bufferOffset = offset,
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {img->width, img->height, 1},
    };
    vkCmdCopyBufferToImage(app->cmd, app->stagingBuffer, img->image, VK_IMAGE_LAYOUT_GENERAL, 1, &region);
}

static void copy_from_image(App *app, const Image *img, VkDeviceSize offset)
{
    VkBufferImageCopy region = {
        .bufferOffset = offset,
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {img->width, img->height, 1},
    };
    vkCmdCopyImageToBuffer(app->cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, app->stagingBuffer, 1, &region);
}

static void memory_barrier(App *app, VkPipelineStageFlags srcStages, VkAccessFlags srcAccess,
                           VkPipelineStageFlags dstStages, VkAccessFlags dstAccess)
{
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = srcAccess,
        .dstAccessMask = dstAccess,
    };
    vkCmdPipelineBarrier(app->cmd, srcStages, dstStages, 0, 1, &barrier, 0, NULL, 0, NULL);
}

static bool begin_commands(App *app)
{
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_TRY(vkBeginCommandBuffer(app->cmd, &begin));
    return true;
}

/* Submits and waits. A real engine keeps frames in flight with fences; waiting keeps this example linear. */
static bool submit_and_wait(App *app)
{
    VK_TRY(vkEndCommandBuffer(app->cmd));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &app->cmd,
    };
    VK_TRY(vkQueueSubmit(app->queue, 1, &submit, VK_NULL_HANDLE));
    VK_TRY(vkQueueWaitIdle(app->queue));
    return true;
}

/* Moves every image to GENERAL, where it stays (dnsr accepts GENERAL, SHADER_READ_ONLY_OPTIMAL and a few more for
 * its inputs; GENERAL keeps this example free of per-frame transitions), and uploads the static G-buffer: depth
 * 0.5, zero motion, normals facing the camera; and the hit distance, the same every frame here (dnsr reads it only
 * where that frame's mask says the ray hit; a tracer writes its rays' distance to their nearest occluder). */
static bool upload_gbuffer(App *app)
{
    Staging *s = app->staging;
    for (uint32_t y = 0; y < HEIGHT; y++) {
        for (uint32_t x = 0; x < WIDTH; x++) {
            s->depth[y][x] = 0.5f;
            s->hitDistance[y][x] = occluder_distance(x);
            /* (0, 0, -1) points back at the camera (at the origin, looking down +z, identity matrices); UNORM
             * normals store n * 0.5 + 0.5 and dnsr decodes them with normalsUnpackMul 2, normalsUnpackAdd -1. */
            s->normals[y][x][0] = 128;
            s->normals[y][x][1] = 128;
            s->normals[y][x][2] = 0;
            s->normals[y][x][3] = 255;
        }
    }
    if (!begin_commands(app)) return false;
    const Image *all[] = {&app->mask, &app->depth, &app->velocity, &app->normals, &app->hitDistance, &app->output};
    VkImageMemoryBarrier toGeneral[6];
    for (int i = 0; i < 6; i++) {
        toGeneral[i] = (VkImageMemoryBarrier){
            .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
            .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
            .newLayout = VK_IMAGE_LAYOUT_GENERAL,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .image = all[i]->image,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
    }
    vkCmdPipelineBarrier(app->cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL, 0,
                         NULL, 6, toGeneral);
    copy_to_image(app, offsetof(Staging, depth), &app->depth);
    copy_to_image(app, offsetof(Staging, hitDistance), &app->hitDistance);
    copy_to_image(app, offsetof(Staging, normals), &app->normals);
    VkClearColorValue zero = {.float32 = {0.0f, 0.0f, 0.0f, 0.0f}};
    VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(app->cmd, app->velocity.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    /* The G-buffer writes must be visible to dnsr's compute reads in later submissions. */
    memory_barrier(app, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    return submit_and_wait(app);
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Frames                                                                                                        */
/* ------------------------------------------------------------------------------------------------------------- */

static DnsrHostImage host_image(const Image *img)
{
    DnsrHostImage h = {img->image, img->view, img->format, VK_IMAGE_LAYOUT_GENERAL, img->width, img->height};
    return h;
}

static void identity(float m[16])
{
    for (int i = 0; i < 16; i++) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

/* Records this frame's denoising. With a real camera the matrices change every frame and the reprojection maps
 * this frame's clip space to the previous one's; this camera never moves. */
static bool record_denoiser(App *app, uint32_t frame)
{
    DnsrShadowsDispatch d = {
        .sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH,
        .commandBuffer = app->cmd,
        .lightIndex = 0,
        .flags = DNSR_DISPATCH_USE_HIT_DISTANCE, /* penumbra guidance: read hitDistance and lightAngularSize */
        .hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS,
        .hitMask = host_image(&app->mask),
        .depth = host_image(&app->depth),
        .velocity = host_image(&app->velocity),
        .normals = host_image(&app->normals),
        .output = host_image(&app->output),
        .hitDistance = host_image(&app->hitDistance),
        .lightAngularSize = LIGHT_ANGULAR_SIZE,
        .motionVectorScale = {1.0f, 1.0f}, /* prev_uv = uv + velocity * scale; our velocity is 0 anyway */
        .normalsUnpackMul = 2.0f,
        .normalsUnpackAdd = -1.0f,
        .eye = {0.0f, 0.0f, 0.0f},
        .frameIndex = frame,
        .depthSimilaritySigma = 1.0f,
        /* Let dnsr emit the barriers around its work: our mask upload (a transfer) before its reads, and its
         * output write before our readback (another transfer). */
        .sync = {
            .inputSrcStages = VK_PIPELINE_STAGE_TRANSFER_BIT,
            .inputSrcAccess = VK_ACCESS_TRANSFER_WRITE_BIT,
            .outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT,
            .outputDstAccess = VK_ACCESS_TRANSFER_READ_BIT,
        },
    };
    identity(d.projectionInverse);
    identity(d.reprojectionMatrix);
    identity(d.viewProjectionInverse);
    DNSR_TRY(dnsr_shadows_record(app->denoiser, &d));
    return true;
}

/* Each frame: trace a fresh 1-spp mask, upload it, denoise, read the output back. */
static bool run_frames(App *app)
{
    for (uint32_t frame = 0; frame < FRAMES; frame++) {
        trace_shadow_rays(app->staging->mask, frame);
        if (!begin_commands(app)) return false;
        /* The previous frame's dnsr passes read the mask image we are about to overwrite. */
        memory_barrier(app, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
        copy_to_image(app, offsetof(Staging, mask), &app->mask);
        if (!record_denoiser(app, frame)) return false;
        copy_from_image(app, &app->output, offsetof(Staging, output));
        memory_barrier(app, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       VK_ACCESS_HOST_READ_BIT);
        if (!submit_and_wait(app)) return false;
    }
    return true;
}

/* Compares the last frame's noisy mask and denoised output with the truth. */
static bool report(App *app)
{
    double truth = 0, noisy = 0, denoised = 0, noisyError = 0, denoisedError = 0;
    for (uint32_t y = 0; y < HEIGHT; y++) {
        for (uint32_t x = 0; x < WIDTH; x++) {
            double v = visibility(x, y);
            double n = is_lit(app->staging->mask, x, y) ? 1.0 : 0.0;
            double o = app->staging->output[y][x];
            truth += v;
            noisy += n;
            denoised += o;
            noisyError += fabs(n - v);
            denoisedError += fabs(o - v);
        }
    }
    double pixels = (double)WIDTH * HEIGHT;
    uint64_t bytes = 0;
    DNSR_TRY(dnsr_context_get_memory_usage(app->denoiser, &bytes));
    printf("dnsr %u.%u.%u on %s: %ux%u, %u frames, push descriptors %s\n", DNSR_VERSION_MAJOR, DNSR_VERSION_MINOR,
           DNSR_VERSION_PATCH, app->deviceName, WIDTH, HEIGHT, FRAMES,
           (app->dnsrFeatures & DNSR_FEATURE_PUSH_DESCRIPTOR) ? "on" : "off");
    printf("               mean   mean abs. error vs truth\n");
    printf("  truth       %.4f\n", truth / pixels);
    printf("  noisy 1 spp %.4f   %.4f\n", noisy / pixels, noisyError / pixels);
    printf("  denoised    %.4f   %.4f\n", denoised / pixels, denoisedError / pixels);
    printf("internal memory: %llu bytes\n", (unsigned long long)bytes);
    if (!(denoisedError < noisyError)) {
        fprintf(stderr, "the denoised output is not closer to the truth than the noisy mask\n");
        return false;
    }
    return true;
}

/* ------------------------------------------------------------------------------------------------------------- */

static void destroy_image(App *app, Image *img)
{
    vkDestroyImageView(app->device, img->view, NULL);
    vkDestroyImage(app->device, img->image, NULL);
    vkFreeMemory(app->device, img->memory, NULL);
}

/* Destroys whatever was created, in reverse order; safe after a failure at any step. */
static void destroy_all(App *app)
{
    if (app->device) {
        vkDeviceWaitIdle(app->device);
        /* The context goes before the device, once the GPU has finished every command buffer it recorded into. */
        if (app->denoiser && dnsr_context_destroy(app->denoiser) != DNSR_SUCCESS)
            fprintf(stderr, "dnsr_context_destroy: %s\n", dnsr_last_error_message());
        Image *images[] = {&app->mask, &app->depth, &app->velocity, &app->normals, &app->hitDistance, &app->output};
        for (int i = 0; i < 6; i++) destroy_image(app, images[i]);
        vkDestroyBuffer(app->device, app->stagingBuffer, NULL);
        vkFreeMemory(app->device, app->stagingMemory, NULL);
        vkDestroyCommandPool(app->device, app->commandPool, NULL);
        vkDestroyDevice(app->device, NULL);
    }
    if (app->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            app->instance, "vkDestroyDebugUtilsMessengerEXT");
        destroy(app->instance, app->messenger, NULL);
    }
    if (app->instance) vkDestroyInstance(app->instance, NULL);
}

int main(int argc, char **argv)
{
    App app = {0};
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--validate") == 0) {
            app.validate = true;
        } else {
            fprintf(stderr, "usage: %s [--validate]\n", argv[0]);
            return 2;
        }
    }
    bool ok = create_instance(&app) && pick_device(&app) && create_device(&app) && create_denoiser(&app) &&
              create_images(&app) && upload_gbuffer(&app) && run_frames(&app) && report(&app);
    destroy_all(&app);
    if (app.validationMessages) {
        fprintf(stderr, "%u validation message(s)\n", app.validationMessages);
        ok = false;
    }
    return ok ? 0 : 1;
}
