// ugv-render: the terrain maps of an LCM log to PNG plan views (the last map, or every Nth).
#include <lcm/lcm-cpp.hpp>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <string>

#include <ugv/terrain_map_t.hpp>

#include "map_render.hpp"
#include "png_writer.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"ugv-render: terrain maps from an LCM log to PNG"};
    app.set_version_flag("--version", std::string("ugv-render ") + UGV_VERSION);
    std::string log_path, out_path = "terrain.png", channel = "TERRAIN_MAP";
    int every = 0;
    ugv::render::RenderOptions o;
    app.add_option("log", log_path, "LCM log with terrain_map_t messages")->required()->check(CLI::ExistingFile);
    app.add_option("-o,--out", out_path, "PNG file; with --every, a prefix: PREFIX-00001.png ...");
    app.add_option("--channel", channel, "channel of the maps");
    app.add_option("--every", every, "render every Nth map (0: only the last)")->check(CLI::NonNegativeNumber);
    app.add_option("--cell-px", o.cell_px, "pixels per cell")->check(CLI::Range(1, 20));
    const std::map<std::string, ugv::render::Layer> layers{
        {"mean", ugv::render::Layer::mean}, {"max", ugv::render::Layer::max}, {"min", ugv::render::Layer::min}};
    app.add_option("--layer", o.layer, "height shown: mean, max (highest sample of a cell) or min (lowest)")
        ->transform(CLI::CheckedTransformer(layers, CLI::ignore_case));
    app.add_flag("--variance", o.variance_panel, "add a panel with the standard deviation");
    app.add_option("--z-min", o.z_min_m, "bottom of the colour scale (m); default: the data's");
    app.add_option("--z-max", o.z_max_m, "top of the colour scale (m); default: the data's");
    app.add_option("--vehicle-rear-x", o.vehicle_rear_x_m, "vehicle outline, body frame (m)");
    app.add_option("--vehicle-front-x", o.vehicle_front_x_m, "vehicle outline, body frame (m)");
    app.add_option("--vehicle-width", o.vehicle_width_m, "vehicle outline (m)");
    CLI11_PARSE(app, argc, argv);

    lcm::LogFile log(log_path, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-render: %s: not an LCM log\n", log_path.c_str());
        return 2;
    }
    ugv::terrain_map_t map, last;
    int maps = 0, written = 0, undecodable = 0;
    bool have_last = false;
    auto write = [&](const ugv::terrain_map_t& m, const std::string& path) {
        const ugv::render::Image img = ugv::render::render_map(m, o);
        if (!ugv::render::write_png(path, img.width(), img.height(), img.rgb())) {
            std::fprintf(stderr, "ugv-render: %s: cannot write\n", path.c_str());
            return false;
        }
        ++written;
        return true;
    };
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != channel) continue;
        if (map.decode(ev->data, 0, ev->datalen) != ev->datalen) {
            ++undecodable;
            continue;
        }
        ++maps;
        if (every > 0 && (maps - 1) % every == 0) {
            char name[32];
            std::snprintf(name, sizeof name, "-%05d.png", maps);
            if (!write(map, out_path + name)) return 1;
        }
        last = map;
        have_last = true;
    }
    if (every == 0) {
        if (!have_last) {
            std::fprintf(stderr, "ugv-render: no decodable map on %s in %s\n", channel.c_str(), log_path.c_str());
            return 1;
        }
        if (!write(last, out_path)) return 1;
    }
    std::printf("%d maps read, %d undecodable, %d PNG written\n", maps, undecodable, written);
    return 0;
}
