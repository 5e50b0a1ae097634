#include <lcm/lcm-cpp.hpp>

#include <cstdio>

#include <ugv/bus/typed.hpp>
#include <ugv/terrain_map_t.hpp>

#include "png_writer.hpp"
#include "render_log.hpp"

namespace ugv::render {

int render_heights_log(const LogJob& job, const RenderOptions& o)
{
    lcm::LogFile log(job.log_path, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-render: %s: not an LCM log\n", job.log_path.c_str());
        return 2;
    }
    terrain_map_t map, last;
    int maps = 0, written = 0, undecodable = 0;
    bool have_last = false;
    auto write = [&](const terrain_map_t& m, const std::string& path) {
        const Image img = render_map(m, o);
        if (!write_png(path, img.width(), img.height(), img.rgb())) {
            std::fprintf(stderr, "ugv-render: %s: cannot write\n", path.c_str());
            return false;
        }
        ++written;
        return true;
    };
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != job.channel) continue;
        if (ev->datalen < 0 || !bus::decode_checked(ev->data, static_cast<std::size_t>(ev->datalen), map)) {
            ++undecodable;
            continue;
        }
        ++maps;
        if (job.every > 0 && (maps - 1) % job.every == 0) {
            char name[32];
            std::snprintf(name, sizeof name, "-%05d.png", maps);
            if (!write(map, job.out_path + name)) return 1;
        }
        last = map;
        have_last = true;
    }
    if (job.every == 0) {
        if (!have_last) {
            std::fprintf(stderr, "ugv-render: no decodable map on %s in %s\n", job.channel.c_str(), job.log_path.c_str());
            return 1;
        }
        if (!write(last, job.out_path)) return 1;
    }
    std::printf("%d maps read, %d undecodable, %d PNG written\n", maps, undecodable, written);
    return 0;
}

}  // namespace ugv::render
