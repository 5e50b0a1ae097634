// ugv-render: the maps of an LCM log to PNG plan views (the last map, or every Nth): the
// terrain maps' heights (map_render), or with --traverse the traversability maps with their
// candidate arcs (traverse_render).
#include <CLI/CLI.hpp>
#include <map>
#include <string>

#include "render_log.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"ugv-render: terrain or traversability maps from an LCM log to PNG"};
    app.set_version_flag("--version", std::string("ugv-render ") + UGV_VERSION);
    ugv::render::LogJob job;
    std::string out_path, channel, arcs_channel = "ARCS";
    bool traverse = false, require_arcs = false;
    ugv::render::RenderOptions o;
    ugv::render::TraverseOptions t;
    app.add_option("log", job.log_path, "LCM log with terrain_map_t (or, with --traverse, traversability_map_t) messages")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("-o,--out", out_path,
                   "PNG file (terrain.png, with --traverse traverse.png); with --every, a prefix: PREFIX-00001.png ...");
    app.add_option("--channel", channel, "channel of the maps (TERRAIN_MAP, with --traverse TRAVERSABILITY_MAP)");
    app.add_option("--every", job.every, "render every Nth map (0: only the last)")->check(CLI::NonNegativeNumber);
    app.add_option("--cell-px", o.cell_px, "pixels per cell")->check(CLI::Range(1, 20));
    app.add_option("--vehicle-rear-x", o.vehicle_rear_x_m, "vehicle outline, body frame (m)");
    app.add_option("--vehicle-front-x", o.vehicle_front_x_m, "vehicle outline, body frame (m)");
    app.add_option("--vehicle-width", o.vehicle_width_m, "vehicle outline (m)");

    auto* trav = app.add_flag("--traverse", traverse,
                              "draw the traversability maps with the candidate arcs of the same terrain map");
    app.add_option("--arcs-channel", arcs_channel, "with --traverse: channel of the arcs")->needs(trav);
    app.add_flag("--require-arcs", require_arcs, "with --traverse: exit 1 when a map drawn has no arcs in the log")
        ->needs(trav);

    const std::map<std::string, ugv::render::Layer> layers{
        {"mean", ugv::render::Layer::mean}, {"max", ugv::render::Layer::max}, {"min", ugv::render::Layer::min}};
    auto* layer = app.add_option("--layer", o.layer, "height shown: mean, max (highest sample of a cell) or min (lowest)")
                      ->transform(CLI::CheckedTransformer(layers, CLI::ignore_case));
    auto* variance = app.add_flag("--variance", o.variance_panel, "add a panel with the standard deviation");
    auto* z_min = app.add_option("--z-min", o.z_min_m, "bottom of the colour scale (m); default: the data's");
    auto* z_max = app.add_option("--z-max", o.z_max_m, "top of the colour scale (m); default: the data's");
    auto* z_span = app.add_option("--z-span", o.z_span_m,
                                  "a colour scale M metres tall, the same in every picture: from M/4 below the "
                                  "ground under the vehicle (the pose's height) to 3M/4 above it")
                       ->check(CLI::PositiveNumber);
    z_span->excludes(z_min)->excludes(z_max);
    for (CLI::Option* height_only : {layer, variance, z_min, z_max, z_span}) trav->excludes(height_only);
    CLI11_PARSE(app, argc, argv);

    job.out_path = !out_path.empty() ? out_path : traverse ? "traverse.png" : "terrain.png";
    job.channel = !channel.empty() ? channel : traverse ? "TRAVERSABILITY_MAP" : "TERRAIN_MAP";
    if (!traverse) return ugv::render::render_heights_log(job, o);
    t.cell_px = o.cell_px;
    t.vehicle_rear_x_m = o.vehicle_rear_x_m;
    t.vehicle_front_x_m = o.vehicle_front_x_m;
    t.vehicle_width_m = o.vehicle_width_m;
    return ugv::render::render_traverse_log(job, arcs_channel, require_arcs, t);
}
