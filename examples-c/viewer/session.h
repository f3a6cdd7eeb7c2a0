// session.h: what a run of the viewer holds, headless or windowed: the options, the scene framed by the orbit
// camera, the lights as the options set them, and the renderer (which owns dnsr's context, denoiser.h).
#pragma once

#include "camera_and_lights.h"
#include "options.h"
#include "renderer.h"
#include "scene_gltf.h"
#include "vk_context.h"

// The Vulkan context options both modes start from: validation as asked, the device VIEWER_DEVICE names.
VulkanContextOptions contextOptions(const Options &options);

struct Session {
    // `ctx` is main's: it outlives the session, so that main can count the validation messages that destroying
    // the session's objects produces.
    Session(const Options &options, const Scene &scene, VulkanContext &ctx);
    ~Session() { renderer.destroy(); }
    Session(const Session &) = delete;
    Session &operator=(const Session &) = delete;

    // Once ctx is created: the renderer for the options, and a line on stdout saying what runs where.
    void createRenderer();

    const Options &opt;
    VulkanContext &ctx;
    SceneFrame scene;
    Orbit orbit0, orbit;  // where the camera started (key R goes back there), where it is
    LightState light;
    // Hybrid mode: whether the renderer has what it needs (--hybrid, or a window with options that allow it: key
    // C), and whether it is on.
    bool hybridAvailable = false, hybrid = false;
    Renderer renderer;
};
