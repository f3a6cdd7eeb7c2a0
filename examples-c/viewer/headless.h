// headless.h: --headless: renders --frames frames with no window system, then writes the last frame's PNGs and
// report.json to --out (README.md lists them).
#pragma once

#include "metrics.h"
#include "options.h"
#include "scene_gltf.h"
#include "vk_context.h"

// `reference`: the file --load-reference loaded (main checked its size), or null. Returns the exit status; throws
// VulkanError (or another std::exception) on a failure. Everything it created is destroyed on return, but `ctx`.
int runHeadless(VulkanContext &ctx, const Options &options, const Scene &scene, const ReferenceFile *reference);
