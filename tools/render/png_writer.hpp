// A minimal PNG writer: 8-bit RGB, no filter, zlib stream of stored (uncompressed) deflate
// blocks, so it needs no library; CRC-32 and Adler-32 computed here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ugv::render {

uint32_t crc32(const uint8_t* data, std::size_t size, uint32_t crc = 0);
uint32_t adler32(const uint8_t* data, std::size_t size);
// The PNG file bytes of an RGB image (rgb: width * height * 3 bytes, rows top to bottom).
std::vector<uint8_t> encode_png(int width, int height, const std::vector<uint8_t>& rgb);
// Writes the file; false on an I/O error.
bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace ugv::render
