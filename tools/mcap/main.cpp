// ugv-mcap: an lcm-logger log into an MCAP file that Foxglove opens (docs/foxglove.md).
//   ugv-mcap LOG OUT.mcap [--channels REGEX] [--no-raw REGEX] [--compression zstd|lz4|none] [--quiet]
// Exit status: 0 converted; 1 converted, but damaged stretches of the log were skipped (the
// events around them are in the file); 2 bad arguments, a missing, empty or non-LCM log, or
// an output that cannot be written.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <regex>
#include <tuple>

#include <CLI/CLI.hpp>

#include "ugv/foxglove/mcap_writer.hpp"
#include "ugv/mcap/lcm_log_scanner.hpp"
#include "ugv/mcap/log_converter.hpp"

namespace {

// The log, mapped read-only.
struct MappedFile
{
    const uint8_t* data = nullptr;
    std::size_t size = 0;
    ~MappedFile()
    {
        if (data) munmap(const_cast<uint8_t*>(data), size);
    }
};

// Returns an error text, empty on success.
std::string map_file(const std::string& path, MappedFile& out)
{
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return std::strerror(errno);
    struct stat st{};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return "not a regular file";
    }
    out.size = static_cast<std::size_t>(st.st_size);
    if (out.size == 0) {
        close(fd);
        return "empty file (no events)";
    }
    void* p = mmap(nullptr, out.size, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    if (p == MAP_FAILED) return std::string("cannot map: ") + std::strerror(errno);
    madvise(p, out.size, MADV_SEQUENTIAL);
    out.data = static_cast<const uint8_t*>(p);
    return {};
}

class FileSink final : public ugv::foxglove::ByteSink
{
public:
    explicit FileSink(std::FILE* f) : f_(f) { std::setvbuf(f_, nullptr, _IOFBF, 1 << 20); }
    void write(const uint8_t* data, std::size_t size) override
    {
        if (!failed_ && std::fwrite(data, 1, size, f_) != size) {
            failed_ = true;
            error_ = errno;
        }
    }
    bool failed() const { return failed_; }
    int error() const { return error_; }

private:
    std::FILE* f_;
    bool failed_ = false;
    int error_ = 0;
};

}  // namespace

int main(int argc, char** argv)
{
    std::string log, out, channels = ".*", no_raw, compression = "zstd";
    bool quiet = false;
    CLI::App app{"ugv-mcap: convert an lcm-logger log into MCAP for Foxglove"};
    app.set_version_flag("--version", std::string("ugv-mcap ") + UGV_VERSION);
    app.add_option("LOG", log, "the lcm-logger log")->required();
    app.add_option("OUT", out, "the MCAP file to write (replaced when it exists)")->required();
    app.add_option("--channels", channels, "only channels matching this regex (whole name)");
    app.add_option("--no-raw", no_raw,
                   "channels whose own JSON topic is left out, keeping their Foxglove topics (e.g. the maps: "
                   "their grids carry every cell)");
    app.add_option("--compression", compression, "chunk compression: zstd, lz4 or none")->capture_default_str();
    ugv::foxglove::McapOptions options;
    auto* zstd_level = app.add_option("--zstd-level", options.zstd_level,
                   "zstd's level: higher packs tighter and slower, below 0 faster and looser (docs/foxglove.md)")
        ->capture_default_str();
    app.add_flag("--quiet", quiet, "no progress on stderr");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "ugv-mcap: %s (see --help)\n", e.what());
        return 2;
    }

    if (!ugv::foxglove::parse_compression(compression, options.compression)) {
        std::fprintf(stderr, "ugv-mcap: --compression '%s': must be zstd, lz4 or none\n", compression.c_str());
        return 2;
    }
    if (zstd_level->count() > 0 && options.compression != ugv::foxglove::Compression::zstd) {
        std::fprintf(stderr, "ugv-mcap: --zstd-level is for --compression zstd, not %s\n", compression.c_str());
        return 2;
    }
    if (options.zstd_level < ugv::foxglove::zstd_min_level() || options.zstd_level > ugv::foxglove::zstd_max_level()) {
        std::fprintf(stderr, "ugv-mcap: --zstd-level %d: must be %d to %d (libzstd's levels)\n", options.zstd_level,
                     ugv::foxglove::zstd_min_level(), ugv::foxglove::zstd_max_level());
        return 2;
    }
    std::regex re, no_raw_re("$^");
    for (auto [option, text, regex] : {std::tuple{"--channels", &channels, &re}, std::tuple{"--no-raw", &no_raw, &no_raw_re}}) {
        if (option == std::string("--no-raw") && text->empty()) continue;
        try {
            *regex = std::regex(*text);
        } catch (const std::regex_error& e) {
            std::fprintf(stderr, "ugv-mcap: %s '%s' is not a valid regex: %s\n", option, text->c_str(), e.what());
            return 2;
        }
    }
    MappedFile file;
    if (const std::string err = map_file(log, file); !err.empty()) {
        std::fprintf(stderr, "ugv-mcap: %s: %s\n", log.c_str(), err.c_str());
        return 2;
    }
    ugv::mcap::LcmLogScanner scanner(file.data, file.size);
    ugv::mcap::LogEvent event;
    if (!scanner.next(event) || scanner.skipped_bytes() > 0) {
        std::fprintf(stderr, "ugv-mcap: %s: not an LCM log (no lcm-logger event at its start)\n", log.c_str());
        return 2;
    }

    // Written beside OUT and renamed at the end: OUT is never a half-written file.
    const std::string part = out + ".part";
    std::FILE* f = std::fopen(part.c_str(), "wb");
    if (!f) {
        std::fprintf(stderr, "ugv-mcap: %s: cannot write: %s\n", part.c_str(), std::strerror(errno));
        return 2;
    }
    FileSink sink(f);
    const auto t0 = std::chrono::steady_clock::now();
    auto next_progress = t0 + std::chrono::seconds(1);
    uint64_t events = 0;
    {
        ugv::foxglove::McapWriter writer(sink, options);
        ugv::mcap::LogConverter converter(writer, re, no_raw_re);
        do {
            converter.add(event);
            // Progress on long logs, at most once a second.
            if (!quiet && (++events & 1023) == 0 && std::chrono::steady_clock::now() >= next_progress) {
                next_progress += std::chrono::seconds(1);
                std::fprintf(stderr, "ugv-mcap: %3.0f %% of %s, %llu events\n", 100.0 * static_cast<double>(scanner.position()) / static_cast<double>(file.size),
                             log.c_str(), static_cast<unsigned long long>(events));
            }
        } while (scanner.next(event) && !sink.failed());
        writer.finish();
        const auto& c = converter.counters();
        const auto& w = writer.counters();
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (std::fclose(f) != 0 && !sink.failed()) {
            std::fprintf(stderr, "ugv-mcap: %s: cannot write: %s\n", part.c_str(), std::strerror(errno));
            std::remove(part.c_str());
            return 2;
        }
        if (sink.failed()) {
            std::fprintf(stderr, "ugv-mcap: %s: cannot write: %s\n", part.c_str(), std::strerror(sink.error()));
            std::remove(part.c_str());
            return 2;
        }
        if (std::rename(part.c_str(), out.c_str()) != 0) {
            std::fprintf(stderr, "ugv-mcap: %s: cannot rename to %s: %s\n", part.c_str(), out.c_str(), std::strerror(errno));
            return 2;
        }
        if (!quiet)
            std::fprintf(stderr,
                         "ugv-mcap: %s: %llu of %llu events converted (%llu left out by --channels, %llu not ugv types, "
                         "%llu malformed), %llu messages on %zu channels in %llu chunks, %.1f MB (%s) in %.2f s\n",
                         out.c_str(), static_cast<unsigned long long>(c.converted),
                         static_cast<unsigned long long>(c.events), static_cast<unsigned long long>(c.filtered),
                         static_cast<unsigned long long>(c.unknown_type), static_cast<unsigned long long>(c.malformed),
                         static_cast<unsigned long long>(c.messages), converter.channel_counts().size(),
                         static_cast<unsigned long long>(w.chunks), static_cast<double>(w.compressed_bytes) / 1e6,
                         compression.c_str(), secs);
    }
    if (scanner.skipped_bytes() > 0) {
        std::fprintf(stderr,
                     "ugv-mcap: %s: damaged from byte %zu: %llu bytes in %llu stretches skipped; the events around them "
                     "are in %s\n",
                     log.c_str(), scanner.first_damage(), static_cast<unsigned long long>(scanner.skipped_bytes()),
                     static_cast<unsigned long long>(scanner.damaged_stretches()), out.c_str());
        return 1;
    }
    return 0;
}
