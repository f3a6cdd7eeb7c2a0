// png_output.h: the viewer's images as 8-bit PNG files (stb_image_write, from Debian's shared libstb).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

// A shadow (0 dark .. 1 lit, clamped) as 8-bit gray.
std::vector<uint8_t> toGray8(const std::vector<float> &v);
// The display image as read back (RGBA8) without its alpha, which is always opaque.
std::vector<uint8_t> rgbaToRgb(const uint8_t *rgba, size_t pixels);
// channels: 1 (gray) or 3 (RGB); rows top to bottom, tightly packed. Throws VulkanError when it cannot write.
void savePng(const std::string &path, uint32_t w, uint32_t h, int channels, const std::vector<uint8_t> &data);
