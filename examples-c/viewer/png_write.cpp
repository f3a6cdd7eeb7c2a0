// png_write.cpp: PNG = signature + IHDR + IDAT (a zlib stream) + IEND, each chunk with a CRC-32. The zlib stream
// here is a sequence of stored (uncompressed) deflate blocks of at most 65535 bytes, followed by an Adler-32.
#include "png_write.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

uint32_t crc32(const uint8_t *data, size_t size, uint32_t crc = 0)
{
    static uint32_t table[256];
    static bool init = false;
    if (!init) {
        for (uint32_t n = 0; n < 256; n++) {
            uint32_t c = n;
            for (int k = 0; k < 8; k++) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            table[n] = c;
        }
        init = true;
    }
    crc ^= 0xffffffffu;
    for (size_t i = 0; i < size; i++) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
    return crc ^ 0xffffffffu;
}

void putBigEndian(std::vector<uint8_t> &out, uint32_t v)
{
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

void chunk(std::vector<uint8_t> &out, const char type[4], const std::vector<uint8_t> &payload)
{
    putBigEndian(out, static_cast<uint32_t>(payload.size()));
    size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), payload.begin(), payload.end());
    putBigEndian(out, crc32(out.data() + start, out.size() - start));  // the CRC covers type + payload
}

}  // namespace

bool writePng(const std::string &path, uint32_t width, uint32_t height, int channels, const uint8_t *pixels,
              std::string *error)
{
    if (channels != 1 && channels != 3 && channels != 4) {
        *error = "unsupported channel count";
        return false;
    }
    // Raw scanlines, each prefixed with filter type 0 (none).
    size_t rowBytes = static_cast<size_t>(width) * channels;
    std::vector<uint8_t> raw;
    raw.reserve((rowBytes + 1) * height);
    for (uint32_t y = 0; y < height; y++) {
        raw.push_back(0);
        raw.insert(raw.end(), pixels + y * rowBytes, pixels + (y + 1) * rowBytes);
    }

    std::vector<uint8_t> zlib = {0x78, 0x01};  // deflate, 32 KiB window, no preset dictionary, fastest level
    size_t offset = 0;
    do {
        size_t n = std::min<size_t>(65535, raw.size() - offset);
        bool last = offset + n == raw.size();
        zlib.push_back(last ? 1 : 0);  // BFINAL bit, BTYPE 00 = stored
        zlib.push_back(static_cast<uint8_t>(n)), zlib.push_back(static_cast<uint8_t>(n >> 8));
        zlib.push_back(static_cast<uint8_t>(~n)), zlib.push_back(static_cast<uint8_t>(~n >> 8));
        zlib.insert(zlib.end(), raw.begin() + offset, raw.begin() + offset + n);
        offset += n;
    } while (offset < raw.size());
    uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
    for (uint8_t byte : raw) a = (a + byte) % 65521, b = (b + a) % 65521;
    putBigEndian(zlib, (b << 16) | a);

    std::vector<uint8_t> ihdr;
    putBigEndian(ihdr, width);
    putBigEndian(ihdr, height);
    const uint8_t colorType = channels == 1 ? 0 : channels == 3 ? 2 : 6;
    ihdr.insert(ihdr.end(), {8, colorType, 0, 0, 0});  // bit depth, colour type, deflate, adaptive, no interlace

    std::vector<uint8_t> file = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    chunk(file, "IHDR", ihdr);
    chunk(file, "IDAT", zlib);
    chunk(file, "IEND", {});

    FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) {
        *error = "cannot open " + path + " for writing";
        return false;
    }
    bool ok = std::fwrite(file.data(), 1, file.size(), f) == file.size();
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) *error = "cannot write " + path;
    return ok;
}
