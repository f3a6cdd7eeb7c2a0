// window.h: window mode (GLFW): the frame shown live, drag to orbit, scroll to zoom, keys for the views (--help lists
// them); --screenshot FILE --frames N saves the displayed image after N frames and exits.
#pragma once

#include "options.h"
#include "scene_gltf.h"
#include "vk_context.h"

// Returns the exit status; throws VulkanError (or another std::exception) on a failure. Everything it created is
// destroyed on return, but `ctx`.
int runWindow(VulkanContext &ctx, const Options &options, const Scene &scene);
