// png_output.cpp: see png_output.h.
#include "png_output.h"

#include <stb_image_write.h>

#include <algorithm>

#include "vk_context.h"

std::vector<uint8_t> toGray8(const std::vector<float> &v)
{
    std::vector<uint8_t> out(v.size());
    for (size_t i = 0; i < v.size(); i++) out[i] = uint8_t(std::clamp(v[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    return out;
}

std::vector<uint8_t> rgbaToRgb(const uint8_t *rgba, size_t pixels)
{
    std::vector<uint8_t> out(pixels * 3);
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++) out[3 * i + c] = rgba[4 * i + c];
    return out;
}

void savePng(const std::string &path, uint32_t w, uint32_t h, int channels, const std::vector<uint8_t> &data)
{
    // stb picks a PNG filter per row and deflates the result; it says only whether the file was written.
    if (!stbi_write_png(path.c_str(), int(w), int(h), channels, data.data(), int(w) * channels))
        throw VulkanError("cannot write " + path);
}
