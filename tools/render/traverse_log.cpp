#include <lcm/lcm-cpp.hpp>

#include <cstdio>

#include <ugv/bus/typed.hpp>

#include "png_writer.hpp"
#include "render_log.hpp"
#include "traverse_pairing.hpp"

namespace ugv::render {

int render_traverse_log(const LogJob& job, const std::string& arcs_channel, bool require_arcs,
                        const TraverseOptions& o)
{
    lcm::LogFile log(job.log_path, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-render: %s: not an LCM log\n", job.log_path.c_str());
        return 2;
    }
    int written = 0, bad_maps = 0, bad_arcs = 0;
    TraversePairing pairing(job.every, [&](const traversability_map_t& m, const candidate_arcs_t* arcs, int index) {
        std::string path = job.out_path;
        if (job.every > 0) {
            char name[32];
            std::snprintf(name, sizeof name, "-%05d.png", index);
            path += name;
        }
        const Image img = render_traverse(m, arcs, o);
        if (!write_png(path, img.width(), img.height(), img.rgb())) {
            std::fprintf(stderr, "ugv-render: %s: cannot write\n", path.c_str());
            return false;
        }
        ++written;
        return true;
    });
    traversability_map_t map;
    candidate_arcs_t arcs;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        const bool is_map = ev->channel == job.channel, is_arcs = ev->channel == arcs_channel;
        if (!is_map && !is_arcs) continue;
        const std::size_t size = ev->datalen < 0 ? 0 : static_cast<std::size_t>(ev->datalen);
        if (is_map) {
            if (!bus::decode_checked(ev->data, size, map) || !drawable(map)) {
                ++bad_maps;
                continue;
            }
            if (!pairing.add_map(map)) return 1;
        } else {
            if (!bus::decode_checked(ev->data, size, arcs) || !drawable(arcs)) {
                ++bad_arcs;
                continue;
            }
            if (!pairing.add_arcs(arcs)) return 1;
        }
    }
    if (job.every == 0 && pairing.maps() == 0) {
        std::fprintf(stderr, "ugv-render: no decodable traversability map on %s in %s (%d undecodable)\n",
                     job.channel.c_str(), job.log_path.c_str(), bad_maps);
        return 1;
    }
    if (!pairing.finish()) return 1;
    std::printf("%d maps read, %d undecodable; %d arcs read, %d undecodable; %d PNG written, %d without arcs\n",
                pairing.maps(), bad_maps, pairing.arcs(), bad_arcs, written, pairing.drawn_without_arcs());
    if (pairing.drawn_without_arcs() > 0) {
        std::fprintf(stderr, "ugv-render: %d map(s) drawn without arcs: none on %s of the same map_seq in %s\n",
                     pairing.drawn_without_arcs(), arcs_channel.c_str(), job.log_path.c_str());
        if (require_arcs) return 1;
    }
    return 0;
}

}  // namespace ugv::render
