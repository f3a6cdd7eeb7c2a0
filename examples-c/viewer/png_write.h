// png_write.h: writes 8-bit PNG files with no dependency (Debian's tinygltf ships without stb_image_write's
// header). The image data is stored uncompressed (deflate "stored" blocks): larger files, but a writer short
// enough to read in one sitting, and every PNG reader accepts it.
#pragma once

#include <cstdint>
#include <string>

// channels: 1 (gray), 3 (RGB) or 4 (RGBA); rows top to bottom, tightly packed. Returns false (and sets *error)
// when the file cannot be written.
bool writePng(const std::string &path, uint32_t width, uint32_t height, int channels, const uint8_t *pixels,
              std::string *error);
