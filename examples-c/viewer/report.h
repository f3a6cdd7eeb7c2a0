// report.h: report.json, what a headless run measured (test.sh and accuracy.py read it; README.md lists its fields).
#pragma once

#include <string>
#include <vector>

#include "metrics.h"
#include "session.h"

// What the headless run measured on its last frame, light by light (light 0 first).
struct Measurements {
    std::vector<ShadowImages> shadows;
    std::vector<ErrorStats> errors;
    uint32_t referenceSamples = 0;  // rays per pixel of the reference measured against
    bool referenceLoaded = false;   // from --load-reference
    TracedStats traced;             // light 0's
    // Each pass's median GPU time over the frames after the first (pipelines warm; the last one's too), and the
    // frames it is over (0 with a single frame: the report then gives the last frame's alone).
    ViewerTimings medianTimings;
    size_t medianFrames = 0;
};

// Throws VulkanError when the file cannot be written.
void writeReport(const std::string &path, const Session &session, const Measurements &m);
