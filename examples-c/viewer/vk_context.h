// vk_context.h: the Vulkan plumbing of the viewer (what any engine already has): instance with optional
// validation, device selection, device creation with what dnsr asks for, buffers, images, compute pipelines and
// the window's swapchain.
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

// Thrown for a failed Vulkan call or a missing capability; main prints the message and exits with status 1.
struct VulkanError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void vkCheck(VkResult result, const char *call);

bool hasDeviceExtension(VkPhysicalDevice physicalDevice, const char *name);

// A zero-initialised Vulkan structure with its sType set (brace-initialising only sType would make -Wextra
// complain about every other member).
template <typename T> T vkStruct(VkStructureType type)
{
    T t{};
    t.sType = type;
    return t;
}
#define VK_CHECK(call) vkCheck((call), #call)

struct GpuBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void *mapped = nullptr;  // host-visible buffers stay mapped
};

struct GpuImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
};

struct VulkanContextOptions {
    bool validate = false;                          // VK_LAYER_KHRONOS_validation + synchronization validation
    std::vector<const char *> instanceExtensions;  // e.g. what GLFW needs for a surface
    std::vector<const char *> deviceExtensions;    // required (VK_KHR_swapchain in window mode)
    std::string deviceSubstring;                    // pick the first device whose name contains it ("" = first)
    // Window mode: whether queue family `family` of a device can present (devices without one are skipped).
    std::function<bool(VkInstance, VkPhysicalDevice, uint32_t)> canPresent;
};

class VulkanContext {
public:
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    uint32_t apiVersion = VK_API_VERSION_1_2;  // what the instance and device were created with
    uint32_t queueFamily = 0;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    bool pushDescriptorEnabled = false;  // VK_KHR_push_descriptor, enabled for dnsr when the device has it
    // shaderStorageImageExtendedFormats, enabled when the device has it: shaders may then write R16_SFLOAT storage
    // images (the hit distance); without it the renderer writes R32_SFLOAT instead.
    bool storageImageExtendedFormats = false;
    unsigned validationMessages = 0;     // warnings and errors the validation layer reported

    void create(const VulkanContextOptions &options);
    void destroy();  // safe after a partial create

    GpuBuffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
    void destroyBuffer(GpuBuffer &buffer);
    GpuImage createImage(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage);
    void destroyImage(GpuImage &image);
    VkPipeline createComputePipeline(VkPipelineLayout layout, const uint32_t *spirv, size_t bytes);

    // One-off work (uploads): begin a command buffer, then submit it and wait for the queue.
    VkCommandBuffer beginOneTimeCommands();
    void submitAndWait(VkCommandBuffer cmd);
    // Copies `bytes` of host data into a device-local buffer through a staging buffer.
    void upload(GpuBuffer &dst, const void *data, VkDeviceSize bytes);

private:
    void createInstance(const VulkanContextOptions &options);
    void pickDevice(const VulkanContextOptions &options);
    void createDevice(const VulkanContextOptions &options);
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
};

// The window's swapchain: images are only ever blit destinations (TRANSFER_DST), then presented.
struct Swapchain {
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    std::vector<VkImage> images;
    std::vector<VkSemaphore> renderFinished;  // one per image: a semaphore a present still waits on is not reused

    void create(VulkanContext &ctx, VkSurfaceKHR surface, uint32_t width, uint32_t height);
    void destroy(VulkanContext &ctx);
};
