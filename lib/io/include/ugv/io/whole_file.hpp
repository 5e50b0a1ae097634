// Whole small files: written so that a crash leaves the old file or the new one, never a mix;
// read only when they are regular files of a bounded size (a FIFO, a device or /proc file
// named by mistake must not block or read without end). Errors are one line in `why`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ugv::io {

// Writes PATH.tmp, fsyncs it, renames it over path and fsyncs the folder.
bool write_file_atomically(const std::string& path, const void* data, std::size_t size, std::string& why);

enum class ReadResult { ok, missing, unreadable, not_a_file, too_large };
// Reads path whole if it is a regular file of at most max_bytes. The type is checked before
// the file is opened (a FIFO or a device is never opened) and again on the opened file; the
// size a file reports is no bound (/proc files say 0), so reading stops one byte past
// max_bytes. `why` completes "PATH ...": "is a FIFO, not a file", "is N bytes, more than M",
// or the system's error for missing and unreadable.
ReadResult read_regular_file(const std::string& path, std::size_t max_bytes, std::vector<uint8_t>& bytes,
                             std::string& why);

}  // namespace ugv::io
