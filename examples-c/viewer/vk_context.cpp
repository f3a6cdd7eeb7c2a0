// vk_context.cpp: see vk_context.h.
#include "vk_context.h"

#include "denoiser.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

void vkCheck(VkResult result, const char *call)
{
    if (result != VK_SUCCESS) throw VulkanError(std::string(call) + " failed: VkResult " + std::to_string(result));
}

namespace {

// The Vulkan loader reports through the same messenger: loader_log() in the loader's log.c sends every message
// with pMessageIdName "Loader Message" and messageIdNumber 0, type GENERAL (GENERAL | VALIDATION for its own
// checks of API usage, PERFORMANCE for performance notes). With VK_INSTANCE_LAYERS set it warns, for example,
// "env var 'VK_INSTANCE_LAYERS' defined and adding layers ...": a remark about the environment, not about what the
// viewer did. Such GENERAL-only loader warnings (and infos) are shown but not counted. Loader errors, the loader's
// VALIDATION messages and everything from the validation layer (whose messages carry a VUID or another id of
// their own) still count.
bool isLoaderNotice(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
                    const VkDebugUtilsMessengerCallbackDataEXT *data)
{
    return types == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT &&
           severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT && data->messageIdNumber == 0 &&
           data->pMessageIdName && std::strcmp(data->pMessageIdName, "Loader Message") == 0;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    if (isLoaderNotice(severity, types, data)) {
        std::fprintf(stderr, "loader notice (not a validation message): %s\n", data->pMessage);
        return VK_FALSE;
    }
    static_cast<VulkanContext *>(user)->validationMessages++;
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

}  // namespace

bool hasDeviceExtension(VkPhysicalDevice physicalDevice, const char *name)
{
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> props(count);
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, props.data());
    for (const VkExtensionProperties &p : props)
        if (std::strcmp(p.extensionName, name) == 0) return true;
    return false;
}

void VulkanContext::create(const VulkanContextOptions &options)
{
    createInstance(options);
    pickDevice(options);
    createDevice(options);
}

void VulkanContext::createInstance(const VulkanContextOptions &options)
{
    auto app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "dnsr-viewer";
    app.apiVersion = VK_API_VERSION_1_2;
    auto info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    std::vector<const char *> extensions = options.instanceExtensions;

    // Validation: the Khronos layer with synchronization validation; every warning or error is counted (the
    // loader's own notices excepted, see isLoaderNotice), and the viewer exits non-zero when there was any.
    const char *layer = "VK_LAYER_KHRONOS_validation";
    VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    auto features = vkStruct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    auto messengerInfo = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidationMessage;
    messengerInfo.pUserData = this;
    if (options.validate) {
        uint32_t count = 0;
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> layers(count);
        vkEnumerateInstanceLayerProperties(&count, layers.data());
        bool found = std::any_of(layers.begin(), layers.end(),
                                 [&](const VkLayerProperties &l) { return std::strcmp(l.layerName, layer) == 0; });
        if (!found) throw VulkanError("--validate: VK_LAYER_KHRONOS_validation is not installed");
        features.pNext = &messengerInfo;  // also reports messages from vkCreateInstance itself
        info.pNext = &features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &layer;
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    if (options.validate) {
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        VK_CHECK(createMessenger(instance, &messengerInfo, nullptr, &messenger));
    }
}

// The first device (whose name contains the requested substring) with Vulkan 1.1+, a compute queue family, the
// required device extensions and, in window mode, presentation from that family.
void VulkanContext::pickDevice(const VulkanContextOptions &options)
{
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    std::string seen;
    for (VkPhysicalDevice candidate : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(candidate, &props);
        seen += std::string(seen.empty() ? "" : ", ") + props.deviceName;
        if (!options.deviceSubstring.empty() && !std::strstr(props.deviceName, options.deviceSubstring.c_str()))
            continue;
        if (props.apiVersion < VK_API_VERSION_1_1) continue;
        bool extensionsOk = std::all_of(options.deviceExtensions.begin(), options.deviceExtensions.end(),
                                        [&](const char *e) { return hasDeviceExtension(candidate, e); });
        if (!extensionsOk) continue;
        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, families.data());
        for (uint32_t f = 0; f < familyCount; f++) {
            // Compute for every pass; timestamps for dnsr's and our timings; presentation in window mode.
            if (!(families[f].queueFlags & VK_QUEUE_COMPUTE_BIT) || families[f].timestampValidBits == 0) continue;
            if (options.canPresent && !options.canPresent(instance, candidate, f)) continue;
            physicalDevice = candidate;
            properties = props;
            queueFamily = f;
            apiVersion = std::min<uint32_t>(VK_API_VERSION_1_2, props.apiVersion & ~0xfffu);  // drop the patch
            return;
        }
    }
    throw VulkanError("no suitable Vulkan device" +
                      (options.deviceSubstring.empty() ? std::string() : " whose name contains '" +
                                                                             options.deviceSubstring + "'") +
                      " (devices: " + (seen.empty() ? "none" : seen) + ")");
}

// Creates the device with every extension dnsr requires, plus VK_KHR_push_descriptor when dnsr can use it and
// the device has it (dnsr then writes its descriptors into the command buffer instead of its own sets): see
// addDenoiserDeviceExtensions in denoiser.cpp.
// The one core feature it enables is the viewer's own: shaderStorageImageExtendedFormats, for the R16_SFLOAT
// hit-distance image its shadow pass writes.
void VulkanContext::createDevice(const VulkanContextOptions &options)
{
    std::vector<const char *> extensions = options.deviceExtensions;
    pushDescriptorEnabled = addDenoiserDeviceExtensions(physicalDevice, apiVersion, extensions);

    VkPhysicalDeviceFeatures available{}, enabled{};
    vkGetPhysicalDeviceFeatures(physicalDevice, &available);
    enabled.shaderStorageImageExtendedFormats = available.shaderStorageImageExtendedFormats;
    storageImageExtendedFormats = available.shaderStorageImageExtendedFormats == VK_TRUE;

    float priority = 1.0f;
    auto queueInfo = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    auto info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.pEnabledFeatures = &enabled;
    VK_CHECK(vkCreateDevice(physicalDevice, &info, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);

    auto poolInfo = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily;
    VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool));
}

void VulkanContext::destroy()
{
    if (device) {
        vkDeviceWaitIdle(device);
        if (commandPool) vkDestroyCommandPool(device, commandPool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroyMessenger(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
    commandPool = VK_NULL_HANDLE, device = VK_NULL_HANDLE, messenger = VK_NULL_HANDLE, instance = VK_NULL_HANDLE;
}

uint32_t VulkanContext::memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const
{
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; i++)
        if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw VulkanError("no memory type with property flags " + std::to_string(flags));
}

GpuBuffer VulkanContext::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible)
{
    GpuBuffer b;
    b.size = size;
    auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    VK_CHECK(vkCreateBuffer(device, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    auto alloc = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memoryType(req.memoryTypeBits, hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                             VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                                                       : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &b.memory));
    VK_CHECK(vkBindBufferMemory(device, b.buffer, b.memory, 0));
    if (hostVisible) VK_CHECK(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

void VulkanContext::destroyBuffer(GpuBuffer &b)
{
    if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device, b.memory, nullptr);  // unmaps too
    b = GpuBuffer{};
}

GpuImage VulkanContext::createImage(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage)
{
    GpuImage img;
    img.format = format, img.width = width, img.height = height;
    auto info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    VK_CHECK(vkCreateImage(device, &info, nullptr, &img.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, img.image, &req);
    auto alloc = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &img.memory));
    VK_CHECK(vkBindImageMemory(device, img.image, img.memory, 0));
    auto view = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    view.image = img.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VK_CHECK(vkCreateImageView(device, &view, nullptr, &img.view));
    return img;
}

void VulkanContext::destroyImage(GpuImage &img)
{
    if (img.view) vkDestroyImageView(device, img.view, nullptr);
    if (img.image) vkDestroyImage(device, img.image, nullptr);
    if (img.memory) vkFreeMemory(device, img.memory, nullptr);
    img = GpuImage{};
}

VkPipeline VulkanContext::createComputePipeline(VkPipelineLayout layout, const uint32_t *spirv, size_t bytes)
{
    auto moduleInfo = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    moduleInfo.codeSize = bytes;
    moduleInfo.pCode = spirv;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));
    auto info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline;
    VkResult r = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    VK_CHECK(r);
    return pipeline;
}

VkCommandBuffer VulkanContext::beginOneTimeCommands()
{
    auto alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &cmd));
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void VulkanContext::submitAndWait(VkCommandBuffer cmd)
{
    VK_CHECK(vkEndCommandBuffer(cmd));
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
    VK_CHECK(vkQueueWaitIdle(queue));
    vkFreeCommandBuffers(device, commandPool, 1, &cmd);
}

void VulkanContext::upload(GpuBuffer &dst, const void *data, VkDeviceSize bytes)
{
    GpuBuffer staging = createBuffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, data, bytes);
    VkCommandBuffer cmd = beginOneTimeCommands();
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer, dst.buffer, 1, &region);
    // Later submissions' shaders read the buffer.
    auto barrier = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    submitAndWait(cmd);
    destroyBuffer(staging);
}

// ---- Swapchain ----

void Swapchain::create(VulkanContext &ctx, VkSurfaceKHR surface, uint32_t width, uint32_t height)
{
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physicalDevice, surface, &caps));
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw VulkanError("the surface's images cannot be blit destinations (no TRANSFER_DST usage)");
    uint32_t formatCount = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, surface, &formatCount, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(formatCount);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, surface, &formatCount, formats.data()));
    // A UNORM format: the composite is gamma-encoded already, and the shadow views are shown as raw values.
    VkSurfaceFormatKHR chosen = formats.empty() ? VkSurfaceFormatKHR{} : formats[0];
    for (const VkSurfaceFormatKHR &f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) {
            chosen = f;
            break;
        }
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, chosen.format, &fp);
    if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT))
        throw VulkanError("the swapchain format cannot be a blit destination");

    extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainKHR old = swapchain;
    auto info = vkStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = surface;
    info.minImageCount = imageCount;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)) {
        for (VkCompositeAlphaFlagBitsKHR a : {VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR, VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                               VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
            if (caps.supportedCompositeAlpha & a) {
                info.compositeAlpha = a;
                break;
            }
    }
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    VK_CHECK(vkCreateSwapchainKHR(ctx.device, &info, nullptr, &swapchain));
    format = chosen.format;
    if (old) vkDestroySwapchainKHR(ctx.device, old, nullptr);

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, swapchain, &count, nullptr));
    images.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, swapchain, &count, images.data()));
    for (VkSemaphore s : renderFinished) vkDestroySemaphore(ctx.device, s, nullptr);
    renderFinished.assign(count, VK_NULL_HANDLE);
    auto semInfo = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    for (VkSemaphore &s : renderFinished) VK_CHECK(vkCreateSemaphore(ctx.device, &semInfo, nullptr, &s));
}

void Swapchain::destroy(VulkanContext &ctx)
{
    for (VkSemaphore s : renderFinished) vkDestroySemaphore(ctx.device, s, nullptr);
    renderFinished.clear();
    if (swapchain) vkDestroySwapchainKHR(ctx.device, swapchain, nullptr);
    swapchain = VK_NULL_HANDLE;
    images.clear();
}
