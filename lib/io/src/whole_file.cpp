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

namespace {

// Why a file of this mode is not a file to read, or nullptr for a regular file.
const char* not_a_file(mode_t mode)
{
    if (S_ISREG(mode)) return nullptr;
    if (S_ISDIR(mode)) return "is a directory, not a file";
    if (S_ISFIFO(mode)) return "is a FIFO, not a file";
    if (S_ISCHR(mode)) return "is a character device, not a file";
    if (S_ISBLK(mode)) return "is a block device, not a file";
    if (S_ISSOCK(mode)) return "is a socket, not a file";
    return "is not a regular file";
}

}  // namespace

ReadResult read_regular_file(const std::string& path, std::size_t max_bytes, std::vector<uint8_t>& bytes,
                             std::string& why)
{
    bytes.clear();
    const auto failed = [&why](ReadResult r, int err) {
        why = std::strerror(err);
        return r;
    };
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0) return failed(errno == ENOENT ? ReadResult::missing : ReadResult::unreadable, errno);
    if (const char* what = not_a_file(st.st_mode)) {
        why = what;
        return ReadResult::not_a_file;
    }
    const auto too_large = [&](std::string what) {
        why = std::move(what);
        bytes.clear();
        return ReadResult::too_large;
    };
    if (static_cast<uint64_t>(st.st_size) > max_bytes) return too_large("is " + std::to_string(st.st_size) + " bytes, more than " + std::to_string(max_bytes));
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return failed(errno == ENOENT ? ReadResult::missing : ReadResult::unreadable, errno);
    struct Closer
    {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    // What was swapped in between stat() and open() is refused too.
    if (::fstat(fd, &st) != 0) return failed(ReadResult::unreadable, errno);
    if (const char* what = not_a_file(st.st_mode)) {
        why = what;
        return ReadResult::not_a_file;
    }
    bytes.reserve(static_cast<std::size_t>(st.st_size));
    uint8_t buf[16384];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int err = errno;
            bytes.clear();
            return failed(ReadResult::unreadable, err);
        }
        if (n == 0) break;
        bytes.insert(bytes.end(), buf, buf + n);
        if (bytes.size() > max_bytes) return too_large("has more than " + std::to_string(max_bytes) + " bytes");
    }
    return ReadResult::ok;
}

}  // namespace ugv::io
