// main.cpp: the dnsr viewer. Loads a glTF scene, ray traces it in compute shaders (G-buffer + one shadow ray
// per pixel), denoises the shadow with dnsr and shows or saves the result.
//
//   dnsr_viewer [scene.gltf|scene.glb] [options]       window (GLFW): drag to orbit, scroll to zoom
//   dnsr_viewer --headless --frames 16 --out out/      PNGs + report.json, no window system needed
//
// Exit status: 0 success; 1 a Vulkan/dnsr failure or (with --validate) any validation message; 2 bad command
// line, a scene or --load-reference file the viewer cannot load (one line on stderr says why).
//
// How the viewer calls dnsr is in denoiser.h / denoiser.cpp: the part to copy into an engine.
#include <cstdio>
#include <exception>

#include "headless.h"
#include "metrics.h"
#include "options.h"
#include "scene_gltf.h"
#include "vk_context.h"
#include "window.h"

int main(int argc, char **argv)
{
    Options options;
    try {
        options = parseOptions(argc, argv);
    } catch (const UsageError &e) {
        std::fprintf(stderr, "viewer: %s (see --help)\n", e.what());
        return 2;
    }

    Scene scene;
    try {
        scene = loadGltfScene(options.scene);
    } catch (const SceneError &e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        return 2;
    } catch (const std::exception &e) {  // e.g. std::bad_alloc for absurd sizes in a malformed file
        std::fprintf(stderr, "viewer: %s: cannot load: %s\n", options.scene.c_str(), e.what());
        return 2;
    }

    ReferenceFile reference;
    if (!options.loadReference.empty()) {
        try {
            reference = loadReference(options.loadReference);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "viewer: %s\n", e.what());
            return 2;
        }
        if (reference.width != options.width || reference.height != options.height) {
            std::fprintf(stderr, "viewer: %s: the reference is %ux%u, this run %ux%u\n",
                         options.loadReference.c_str(), reference.width, reference.height, options.width, options.height);
            return 2;
        }
    }

    // The context outlives the run, so that the validation messages its objects' destruction produces count too.
    VulkanContext ctx;
    int status = 1;
    try {
        status = options.headless
                     ? runHeadless(ctx, options, scene, options.loadReference.empty() ? nullptr : &reference)
                     : runWindow(ctx, options, scene);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        status = 1;
    }
    ctx.destroy();
    if (ctx.validationMessages) {
        std::fprintf(stderr, "viewer: %u validation message(s)\n", ctx.validationMessages);
        return 1;
    }
    return status;
}
