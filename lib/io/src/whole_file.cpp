#include "ugv/io/whole_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace ugv::io {

bool write_file_atomically(const std::string& path, const void* data, std::size_t size, std::string& why)
{
    const std::string tmp = path + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        why = tmp + ": " + std::strerror(errno);
        return false;
    }
    const auto* p = static_cast<const uint8_t*>(data);
    std::size_t done = 0;
    int err = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, p + done, size - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : ENOSPC;
            break;
        }
        done += static_cast<std::size_t>(n);
    }
    if (done == size && ::fsync(fd) != 0) err = errno;
    ::close(fd);
    if (done != size || err != 0) {
        why = tmp + ": " + std::strerror(err);
        ::unlink(tmp.c_str());
        return false;
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        why = path + ": " + std::strerror(errno);
        ::unlink(tmp.c_str());
        return false;
    }
    // The rename itself is durable only once the folder is.
    const std::string dir = std::filesystem::path(path).parent_path().string();
    if (const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return true;
}

ReadResult read_regular_file(const std::string& path, std::size_t max_bytes, std::vector<uint8_t>& bytes,
                             std::string& why)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        const int err = errno;
        why = std::strerror(err);
        return err == ENOENT ? ReadResult::missing : ReadResult::refused;
    }
    struct stat st{};
    ReadResult result = ReadResult::refused;
    if (::fstat(fd, &st) != 0) {
        why = std::strerror(errno);
    } else if (!S_ISREG(st.st_mode)) {
        why = S_ISDIR(st.st_mode) ? "a directory, not a regular file" : "not a regular file";
    } else if (static_cast<uint64_t>(st.st_size) > max_bytes) {
        why = std::to_string(st.st_size) + " bytes, more than " + std::to_string(max_bytes);
    } else {
        bytes.resize(static_cast<std::size_t>(st.st_size));
        std::size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        // A file that changed size while read is read again next time, not half-used.
        uint8_t extra = 0;
        if (done == bytes.size() && ::read(fd, &extra, 1) == 0) {
            result = ReadResult::ok;
        } else {
            why = "changed while read";
            bytes.clear();
        }
    }
    ::close(fd);
    return result;
}

}  // namespace ugv::io
