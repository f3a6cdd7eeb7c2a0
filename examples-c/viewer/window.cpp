// window.cpp: see window.h.
#include "window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "png_output.h"
#include "session.h"

namespace {

class Window {
public:
    Window(const Options &options, const Scene &scene, VulkanContext &ctx) : s_(options, scene, ctx), ctx_(ctx)
    {
        view_ = options.view;
    }

    // In the order that works: the renderer and everything on the device, the surface, the instance, and GLFW last
    // (its window system connection outlives the Vulkan objects made from it).
    ~Window()
    {
        if (ctx_.device) vkDeviceWaitIdle(ctx_.device);
        s_.renderer.destroy();
        if (ctx_.device) {
            if (fence_) vkDestroyFence(ctx_.device, fence_, nullptr);
            if (imageAvailable_) vkDestroySemaphore(ctx_.device, imageAvailable_, nullptr);
            swapchain_.destroy(ctx_);
        }
        if (surface_) vkDestroySurfaceKHR(ctx_.instance, surface_, nullptr);
        ctx_.destroy();
        if (window_) glfwDestroyWindow(window_);
        if (glfwStarted_) glfwTerminate();
    }

    int run()
    {
        createWindow();
        VulkanContextOptions vo = contextOptions(s_.opt);
        uint32_t count = 0;
        const char **glfwExtensions = glfwGetRequiredInstanceExtensions(&count);
        if (!glfwExtensions) throw VulkanError("GLFW cannot create Vulkan surfaces here");
        vo.instanceExtensions.assign(glfwExtensions, glfwExtensions + count);
        vo.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        vo.canPresent = [](VkInstance instance, VkPhysicalDevice pd, uint32_t family) {
            return glfwGetPhysicalDevicePresentationSupport(instance, pd, family) == GLFW_TRUE;
        };
        ctx_.create(vo);
        VK_CHECK(glfwCreateWindowSurface(ctx_.instance, window_, nullptr, &surface_));
        VkBool32 supported = VK_FALSE;
        VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx_.physicalDevice, ctx_.queueFamily, surface_, &supported));
        if (!supported) throw VulkanError("the chosen queue family cannot present to this window");
        recreateSwapchain();
        s_.createRenderer();

        auto semInfo = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        VK_CHECK(vkCreateSemaphore(ctx_.device, &semInfo, nullptr, &imageAvailable_));
        auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        VK_CHECK(vkCreateFence(ctx_.device, &fenceInfo, nullptr, &fence_));
        auto alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = ctx_.commandPool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VkCommandBuffer cmd;
        VK_CHECK(vkAllocateCommandBuffers(ctx_.device, &alloc, &cmd));

        using Clock = std::chrono::steady_clock;
        auto lastTitle = Clock::now(), lastFrame = Clock::now();
        uint32_t framesSinceTitle = 0, frame = 0;
        Orbit lastOrbit = s_.orbit;
        float lastAzimuth = s_.light.azimuth;
        cameraCut_ = true;
        while (!glfwWindowShouldClose(window_)) {
            glfwPollEvents();
            int fbw = 0, fbh = 0;
            glfwGetFramebufferSize(window_, &fbw, &fbh);
            if (fbw == 0 || fbh == 0) {  // minimised: nothing to present to
                glfwWaitEvents();
                continue;
            }
            auto now = Clock::now();
            float dt = std::chrono::duration<float>(now - lastFrame).count();
            lastFrame = now;
            if (s_.light.moving) s_.light.azimuth += radians(20.0f) * std::min(dt, 0.1f);

            uint32_t imageIndex = 0;
            VkResult acquired = vkAcquireNextImageKHR(ctx_.device, swapchain_.swapchain, UINT64_MAX, imageAvailable_,
                                                      VK_NULL_HANDLE, &imageIndex);
            if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
                recreateSwapchain();
                continue;
            }
            if (acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);

            FrameInput in = makeFrame(s_.scene, s_.orbit, s_.light, s_.opt.width, s_.opt.height);
            in.cameraCut = cameraCut_;
            in.display = view_;
            in.shownLight = shownLight_;
            in.hybrid = s_.hybrid;
            // The reference accumulates while nothing moves (view 3 shows it converging); any change restarts it.
            bool changed = std::memcmp(&lastOrbit, &s_.orbit, sizeof s_.orbit) != 0 || lastAzimuth != s_.light.azimuth;
            in.resetReference = changed || cameraCut_;
            uint32_t have = in.resetReference ? 0 : s_.renderer.referenceCount();
            if (view_ == View::Reference && have < s_.opt.referenceSamples)
                in.referenceSamples = std::min(8u, s_.opt.referenceSamples - have);
            lastOrbit = s_.orbit;
            lastAzimuth = s_.light.azimuth;
            cameraCut_ = false;

            VK_CHECK(vkResetCommandBuffer(cmd, 0));
            auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
            begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
            VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
            s_.renderer.recordFrame(cmd, in);
            recordBlit(cmd, imageIndex);
            VK_CHECK(vkEndCommandBuffer(cmd));

            VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
            auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
            submit.waitSemaphoreCount = 1;
            submit.pWaitSemaphores = &imageAvailable_;
            submit.pWaitDstStageMask = &waitStage;
            submit.commandBufferCount = 1;
            submit.pCommandBuffers = &cmd;
            submit.signalSemaphoreCount = 1;
            submit.pSignalSemaphores = &swapchain_.renderFinished[imageIndex];
            VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &submit, fence_));

            auto present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
            present.waitSemaphoreCount = 1;
            present.pWaitSemaphores = &swapchain_.renderFinished[imageIndex];
            present.swapchainCount = 1;
            present.pSwapchains = &swapchain_.swapchain;
            present.pImageIndices = &imageIndex;
            VkResult presented = vkQueuePresentKHR(ctx_.queue, &present);

            // One frame in flight: wait for this one before recording the next (and before reading timings).
            VK_CHECK(vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
            VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));
            s_.renderer.afterFrame();
            if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) recreateSwapchain();
            else VK_CHECK(presented);

            frame++;
            framesSinceTitle++;
            double since = std::chrono::duration<double>(Clock::now() - lastTitle).count();
            if (since >= 1.0) {
                updateTitle(framesSinceTitle / since);
                lastTitle = Clock::now();
                framesSinceTitle = 0;
            }
            if (s_.opt.frames && frame >= s_.opt.frames) {
                if (!s_.opt.screenshot.empty()) saveScreenshot();
                break;
            }
        }
        vkDeviceWaitIdle(ctx_.device);
        vkFreeCommandBuffers(ctx_.device, ctx_.commandPool, 1, &cmd);
        return 0;
    }

private:
    static Window &self(GLFWwindow *w) { return *static_cast<Window *>(glfwGetWindowUserPointer(w)); }

    void onKey(int key, int action)
    {
        if (action != GLFW_PRESS) return;
        switch (key) {
        case GLFW_KEY_ESCAPE:
        case GLFW_KEY_Q: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
        case GLFW_KEY_R:
            s_.orbit = s_.orbit0;
            cameraCut_ = true;  // a jump: dnsr's history no longer matches
            break;
        case GLFW_KEY_1: view_ = View::Noisy; break;
        case GLFW_KEY_2: view_ = View::Denoised; break;
        case GLFW_KEY_3: view_ = View::Reference; break;
        case GLFW_KEY_4: view_ = View::Composite; break;
        case GLFW_KEY_5: view_ = View::TileDensity; break;
        case GLFW_KEY_6: view_ = View::DnsrTiles; break;
        case GLFW_KEY_7: view_ = View::DnsrSampleCount; break;
        case GLFW_KEY_8: view_ = View::DnsrVariance; break;
        case GLFW_KEY_9: view_ = View::DnsrDisocclusion; break;
        case GLFW_KEY_U: view_ = View::DnsrSampleRun; break;
        case GLFW_KEY_L: s_.light.moving = !s_.light.moving; break;
        case GLFW_KEY_H: s_.light.hitDistance = !s_.light.hitDistance; break;
        case GLFW_KEY_N: shownLight_ = (shownLight_ + 1) % s_.opt.lights; break;
        case GLFW_KEY_0: view_ = View::Hybrid; break;
        case GLFW_KEY_T: view_ = View::TracedTiles; break;
        case GLFW_KEY_C:
            if (s_.hybridAvailable) s_.hybrid = !s_.hybrid;
            else std::printf("viewer: no hybrid mode: it %s\n", hybridUnsupported(s_.opt).c_str());
            break;
        default: break;
        }
    }

    void onCursor(double x, double y)
    {
        if (dragging_) {
            s_.orbit.yaw -= radians(0.3f) * float(x - lastX_);
            s_.orbit.pitch =
                std::clamp(s_.orbit.pitch + radians(0.3f) * float(y - lastY_), radians(-85.0f), radians(85.0f));
        }
        lastX_ = x, lastY_ = y;
    }

    void createWindow()
    {
        glfwSetErrorCallback([](int, const char *msg) { std::fprintf(stderr, "glfw: %s\n", msg); });
        if (!glfwInit()) throw VulkanError("cannot initialise GLFW (no display? use --headless)");
        glfwStarted_ = true;
        if (!glfwVulkanSupported()) throw VulkanError("GLFW found no Vulkan loader");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        window_ = glfwCreateWindow(int(s_.opt.width), int(s_.opt.height), "dnsr viewer", nullptr, nullptr);
        if (!window_) throw VulkanError("cannot create a window");
        glfwSetWindowUserPointer(window_, this);
        glfwSetKeyCallback(window_, [](GLFWwindow *w, int key, int, int action, int) { self(w).onKey(key, action); });
        glfwSetCursorPosCallback(window_, [](GLFWwindow *w, double x, double y) { self(w).onCursor(x, y); });
        glfwSetMouseButtonCallback(window_, [](GLFWwindow *w, int button, int action, int) {
            if (button == GLFW_MOUSE_BUTTON_LEFT) self(w).dragging_ = action == GLFW_PRESS;
        });
        glfwSetScrollCallback(window_, [](GLFWwindow *w, double, double dy) {
            Orbit &o = self(w).s_.orbit;
            o.distance = std::clamp(o.distance * std::pow(0.9f, float(dy)), 1e-3f * self(w).s_.scene.radius,
                                    20.0f * self(w).s_.scene.radius);
        });
    }

    void recreateSwapchain()
    {
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window_, &fbw, &fbh);
        vkDeviceWaitIdle(ctx_.device);
        swapchain_.create(ctx_, surface_, uint32_t(std::max(fbw, 1)), uint32_t(std::max(fbh, 1)));
    }

    // Scales the display image onto the swapchain image and makes it presentable.
    void recordBlit(VkCommandBuffer cmd, uint32_t imageIndex)
    {
        VkImage target = swapchain_.images[imageIndex];
        auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.srcAccessMask = 0;
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // the previous contents are not needed
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = target;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        // Source stage TRANSFER: the acquire semaphore's wait is at the transfer stage, so this chains after it.
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
        const GpuImage &src = s_.renderer.displayImage();
        VkImageBlit region{};
        region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.srcOffsets[1] = {int32_t(src.width), int32_t(src.height), 1};
        region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.dstOffsets[1] = {int32_t(swapchain_.extent.width), int32_t(swapchain_.extent.height), 1};
        vkCmdBlitImage(cmd, src.image, VK_IMAGE_LAYOUT_GENERAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                       VK_FILTER_NEAREST);  // nearest: the pixels dnsr produced, not a smoothed version of them
        b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.dstAccessMask = 0;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
    }

    void updateTitle(double fps)
    {
        const char *names[] = {"noisy",
                               "denoised",
                               "reference",
                               "composite",
                               "tile density",
                               "dnsr tile classification (1 lit, 0 shadow, 0.5 filtered, 0.75 sky)",
                               "dnsr sample count",
                               "dnsr variance (std dev)",
                               "dnsr disocclusion (history restarted)",
                               "hybrid: cascades lit pale / shadowed blue, rays lit orange / occluded red",
                               "hybrid: pixels traced per tile (grey none, red few, yellow all)"};
        char title[512];
        const DnsrPassTimings &t = s_.renderer.dnsrTimings;
        double filter = 0;
        for (uint32_t p = 0; p < t.filterPasses && p < 4; p++) filter += t.filterMs[p];
        const ViewerTimings &v = s_.renderer.viewerTimings;
        char view[64];
        std::snprintf(view, sizeof view, view_ == View::Reference ? "%s (%u rays/px)" : "%s", names[uint32_t(view_)],
                      s_.renderer.referenceCount());
        char shown[32] = "";  // the light the view shows (key N), where there is a choice
        if (s_.opt.lights > 1 && view_ != View::Composite) std::snprintf(shown, sizeof shown, ", light %u", shownLight_);
        char hybrid[96] = "";  // hybrid mode's own passes, when it is on
        if (s_.hybrid)
            std::snprintf(hybrid, sizeof hybrid, " | hybrid: cascades %.2f, classify %.2f ms", v.cascades, v.classify);
        std::snprintf(title, sizeof title,
                      "dnsr viewer | %s%s%s | guidance %s%s | dnsr GPU ms: prepare %.2f, tiles %.2f, filter %.2f (%u "
                      "passes), total %.2f | rays ms: primary %.2f, shadow %.2f | %.1f fps",
                      view, shown, s_.light.moving ? " | light moving" : "",
                      s_.light.hitDistance ? "on" : "off", hybrid, t.prepareMs, t.tileClassificationMs,
                      filter, t.filterPasses, t.totalMs, v.primary, v.shadow, fps);
        glfwSetWindowTitle(window_, title);
    }

    // Saves the image that was just blit to the window (the display image, at render size).
    void saveScreenshot()
    {
        VkCommandBuffer cmd = ctx_.beginOneTimeCommands();
        s_.renderer.recordReadback(cmd);
        ctx_.submitAndWait(cmd);
        savePng(s_.opt.screenshot, s_.opt.width, s_.opt.height, 3,
                rgbaToRgb(s_.renderer.readDisplay(), size_t(s_.opt.width) * s_.opt.height));
        std::printf("viewer: wrote %s after %u frames\n", s_.opt.screenshot.c_str(), s_.opt.frames);
    }

    Session s_;
    VulkanContext &ctx_;
    View view_ = View::Composite;
    uint32_t shownLight_ = 0;  // the light the views other than the composite show (key N)
    bool cameraCut_ = true;

    GLFWwindow *window_ = nullptr;
    bool glfwStarted_ = false;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    Swapchain swapchain_;
    VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool dragging_ = false;
    double lastX_ = 0, lastY_ = 0;
};

}  // namespace

int runWindow(VulkanContext &ctx, const Options &options, const Scene &scene)
{
    Window window(options, scene, ctx);
    return window.run();
}
