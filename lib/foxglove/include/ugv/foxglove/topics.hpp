// The LCM -> Foxglove mapping, shared by ugv-mcap and a live bridge: which topics a channel
// becomes, their JSON Schemas, and each message as JSON. No I/O.
//
// Every channel is a topic of its own name with the message as JSON (as ugv-dump prints it)
// and a JSON Schema generated from the type's reflection (lcmtypes/gen_reflect.py). Types
// Foxglove can draw get a second topic, `<CHANNEL>/<suffix>`, in a well-known Foxglove
// schema, also JSON (docs/foxglove.md has the table).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::foxglove {

enum class TopicKind {
    raw,              // the LCM message itself; schema from the reflection
    terrain_grid,     // terrain_map_t -> foxglove.Grid
    traverse_grid,    // traversability_map_t -> foxglove.Grid
    laser_scan,       // laser_scan_t -> foxglove.LaserScan (frame laser)
    point_cloud,      // point_cloud_t -> foxglove.PointCloud (frame body)
    pose_transform,   // pose_t -> foxglove.FrameTransform world -> body
    pose_in_frame,    // pose_t -> foxglove.PoseInFrame (frame world)
    laser_transform,  // servo_state_t -> foxglove.FrameTransform body -> laser
    location_fix,     // gps_fix_t -> foxglove.LocationFix
    arcs_scene,       // candidate_arcs_t -> foxglove.SceneUpdate (lines, frame world)
    status_log,       // daemon_status_t -> foxglove.Log, on a change of state or error only
};

struct TopicSpec
{
    std::string topic;        // e.g. "TERRAIN_MAP" or "TERRAIN_MAP/grid"
    std::string schema_name;  // e.g. "ugv.terrain_map_t" or "foxglove.Grid"
    std::string type_name;    // the LCM type, e.g. "ugv.terrain_map_t"
    TopicKind kind = TopicKind::raw;
};

// The topics of a channel that carries type_name (a ugv type, as reflect names it): the raw
// topic first (unless with_raw is false: ugv-mcap --no-raw, ugv-foxglove's no_raw), then the
// well-known ones. Empty for a type that is not a ugv type. ugv-mcap and ugv-foxglove both
// take their topics from here.
std::vector<TopicSpec> topics_for(std::string_view channel, std::string_view type_name, bool with_raw = true);

// The JSON Schema (schema encoding "jsonschema") of a topic's messages.
std::string schema_of(const TopicSpec& spec);

// A JSON Schema of a ugv type generated from its reflected fields; empty for an unknown type.
// Floats may be null (NaN and Inf print as null).
std::string lcm_json_schema(std::string_view type_name);

// The frames the transforms name.
inline constexpr const char* kWorldFrame = "world";  // local ENU of the pose's datum
inline constexpr const char* kBodyFrame = "body";
inline constexpr const char* kLaserFrame = "laser";

struct ConverterCounters
{
    uint64_t converted = 0;   // JSON messages produced
    uint64_t malformed = 0;   // messages that did not decode as their topic's type
    uint64_t unchanged = 0;   // status messages without a change of state (no Log)

    template <typename F>
    void visit(F&& f) const
    {
        f("converted", converted);
        f("malformed", malformed);
        f("unchanged", unchanged);
    }
};

// Turns messages into JSON for their topics. Holds state: the last status of each channel
// (a Log is made on a change only) and the laser's origin from the last point cloud.
class Converter
{
public:
    Converter();
    ~Converter();
    Converter(const Converter&) = delete;
    Converter& operator=(const Converter&) = delete;

    // Fills json for one message of spec's channel. False when the topic gets nothing for
    // this message (a status without a change) or the bytes do not decode (counted).
    // same_message: the bytes are those of the previous call, for another topic of the same
    // channel (a map is then not decoded again for its grid).
    bool convert(const TopicSpec& spec, const uint8_t* data, std::size_t size, std::string& json,
                 bool same_message = false);

    const ConverterCounters& counters() const { return counters_; }

private:
    struct StatusSeen
    {
        int state = -1;
        std::string last_error;
    };
    struct Decoded;
    std::unique_ptr<Decoded> decoded_;
    std::map<std::string, StatusSeen, std::less<>> status_;
    double laser_origin_[3] = {0, 0, 0};
    ConverterCounters counters_;
};

}  // namespace ugv::foxglove
