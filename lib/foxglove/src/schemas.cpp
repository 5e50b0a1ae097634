// JSON Schemas: the ugv types' generated from their reflected fields, and the Foxglove
// well-known schemas' field layouts (Foxglove's published message schemas, JSON encoding:
// times as {sec, nsec}, bytes as base64 strings, enums as their numbers).
#include <initializer_list>
#include <stdexcept>
#include <utility>

#include "ugv/foxglove/topics.hpp"
#include "ugv/reflect.hpp"

namespace ugv::foxglove {
namespace {

using Props = std::initializer_list<std::pair<const char*, std::string>>;

std::string quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

std::string object(Props props, std::string_view title = {})
{
    std::string s = "{";
    if (!title.empty()) s += "\"title\":" + quoted(title) + ",";
    s += "\"type\":\"object\",\"properties\":{";
    bool first = true;
    for (const auto& [name, schema] : props) {
        if (!first) s += ',';
        first = false;
        s += quoted(name) + ":" + schema;
    }
    return s + "}}";
}

std::string array_of(const std::string& items, int length = 0)
{
    std::string s = "{\"type\":\"array\",\"items\":" + items;
    if (length > 0) s += ",\"minItems\":" + std::to_string(length) + ",\"maxItems\":" + std::to_string(length);
    return s + "}";
}

const std::string kNumber = "{\"type\":\"number\"}";
const std::string kString = "{\"type\":\"string\"}";
const std::string kBool = "{\"type\":\"boolean\"}";
const std::string kUint = "{\"type\":\"integer\",\"minimum\":0}";
const std::string kBytes = "{\"type\":\"string\",\"contentEncoding\":\"base64\"}";
std::string enumeration(int max) { return "{\"type\":\"integer\",\"minimum\":0,\"maximum\":" + std::to_string(max) + "}"; }

std::string time_schema() { return object({{"sec", kUint}, {"nsec", "{\"type\":\"integer\",\"minimum\":0,\"maximum\":999999999}"}}); }
std::string vector3() { return object({{"x", kNumber}, {"y", kNumber}, {"z", kNumber}}); }
std::string quaternion() { return object({{"x", kNumber}, {"y", kNumber}, {"z", kNumber}, {"w", kNumber}}); }
std::string pose() { return object({{"position", vector3()}, {"orientation", quaternion()}}); }
std::string color() { return object({{"r", kNumber}, {"g", kNumber}, {"b", kNumber}, {"a", kNumber}}); }
// NumericType: 0 UNKNOWN, 1 UINT8, 2 INT8, 3 UINT16, 4 INT16, 5 UINT32, 6 INT32, 7 FLOAT32, 8 FLOAT64.
std::string packed_fields() { return array_of(object({{"name", kString}, {"offset", kUint}, {"type", enumeration(8)}})); }

std::string grid()
{
    return object({{"timestamp", time_schema()}, {"frame_id", kString}, {"pose", pose()}, {"column_count", kUint},
                   {"cell_size", object({{"x", kNumber}, {"y", kNumber}})}, {"row_stride", kUint},
                   {"cell_stride", kUint}, {"fields", packed_fields()}, {"data", kBytes}},
                  "foxglove.Grid");
}

std::string laser_scan()
{
    return object({{"timestamp", time_schema()}, {"frame_id", kString}, {"pose", pose()}, {"start_angle", kNumber},
                   {"end_angle", kNumber}, {"ranges", array_of(kNumber)}, {"intensities", array_of(kNumber)}},
                  "foxglove.LaserScan");
}

std::string point_cloud()
{
    return object({{"timestamp", time_schema()}, {"frame_id", kString}, {"pose", pose()}, {"point_stride", kUint},
                   {"fields", packed_fields()}, {"data", kBytes}},
                  "foxglove.PointCloud");
}

std::string frame_transform()
{
    return object({{"timestamp", time_schema()}, {"parent_frame_id", kString}, {"child_frame_id", kString},
                   {"translation", vector3()}, {"rotation", quaternion()}},
                  "foxglove.FrameTransform");
}

std::string pose_in_frame()
{
    return object({{"timestamp", time_schema()}, {"frame_id", kString}, {"pose", pose()}}, "foxglove.PoseInFrame");
}

std::string location_fix()
{
    // position_covariance_type: 0 UNKNOWN, 1 APPROXIMATED, 2 DIAGONAL_KNOWN, 3 KNOWN.
    return object({{"timestamp", time_schema()}, {"frame_id", kString}, {"latitude", kNumber}, {"longitude", kNumber},
                   {"altitude", kNumber}, {"position_covariance", array_of(kNumber, 9)},
                   {"position_covariance_type", enumeration(3)}},
                  "foxglove.LocationFix");
}

std::string scene_update()
{
    // LinePrimitive type: 0 LINE_STRIP, 1 LINE_LOOP, 2 LINE_LIST. The primitives this
    // converter never fills are listed as arrays of objects.
    const std::string line = object({{"type", enumeration(2)}, {"pose", pose()}, {"thickness", kNumber},
                                     {"scale_invariant", kBool}, {"points", array_of(vector3())}, {"color", color()},
                                     {"colors", array_of(color())}, {"indices", array_of(kUint)}});
    const std::string any_objects = array_of("{\"type\":\"object\"}");
    const std::string entity = object({{"timestamp", time_schema()}, {"frame_id", kString}, {"id", kString},
                                       {"lifetime", object({{"sec", kUint}, {"nsec", kUint}})}, {"frame_locked", kBool},
                                       {"metadata", array_of(object({{"key", kString}, {"value", kString}}))},
                                       {"arrows", any_objects}, {"cubes", any_objects}, {"spheres", any_objects},
                                       {"cylinders", any_objects}, {"lines", array_of(line)}, {"triangles", any_objects},
                                       {"texts", any_objects}, {"models", any_objects}});
    // SceneEntityDeletion type: 0 MATCHING_ID, 1 ALL.
    const std::string deletion = object({{"timestamp", time_schema()}, {"type", enumeration(1)}, {"id", kString}});
    return object({{"deletions", array_of(deletion)}, {"entities", array_of(entity)}}, "foxglove.SceneUpdate");
}

std::string log()
{
    // level: 0 UNKNOWN, 1 DEBUG, 2 INFO, 3 WARNING, 4 ERROR, 5 FATAL.
    return object({{"timestamp", time_schema()}, {"level", enumeration(5)}, {"message", kString}, {"name", kString},
                   {"file", kString}, {"line", kUint}},
                  "foxglove.Log");
}

std::string primitive_schema(std::string_view type)
{
    if (type == "float" || type == "double") return "{\"type\":[\"number\",\"null\"]}";  // NaN, Inf -> null
    if (type == "int8_t") return "{\"type\":\"integer\",\"minimum\":-128,\"maximum\":127}";
    if (type == "int16_t") return "{\"type\":\"integer\",\"minimum\":-32768,\"maximum\":32767}";
    if (type == "int32_t") return "{\"type\":\"integer\",\"minimum\":-2147483648,\"maximum\":2147483647}";
    if (type == "int64_t") return "{\"type\":\"integer\"}";
    if (type == "byte") return "{\"type\":\"integer\",\"minimum\":0,\"maximum\":255}";
    if (type == "boolean") return "{\"type\":\"integer\",\"minimum\":0,\"maximum\":1}";  // printed as 0 or 1
    if (type == "string") return kString;
    return {};
}

std::string type_schema(std::string_view type_name, int depth)
{
    const auto* fields = reflect::fields_of(type_name);
    if (!fields || depth > 8) return {};
    std::string props, required;
    for (const auto& f : *fields) {
        std::string item = primitive_schema(f.type);
        if (item.empty()) item = type_schema(f.type, depth + 1);
        if (item.empty()) throw std::logic_error("lcm_json_schema: " + std::string(f.type) + " is not a known type");
        if (f.fixed_length > 0) item = array_of(item, f.fixed_length);
        else if (!f.length_field.empty()) item = array_of(item);
        if (!props.empty()) props += ',';
        props += quoted(f.name) + ":" + item;
        if (!required.empty()) required += ',';
        required += quoted(f.name);
    }
    return "{\"title\":" + quoted(type_name) + ",\"type\":\"object\",\"properties\":{" + props + "},\"required\":[" +
           required + "]}";
}

}  // namespace

std::string lcm_json_schema(std::string_view type_name) { return type_schema(type_name, 0); }

std::string schema_of(const TopicSpec& spec)
{
    switch (spec.kind) {
    case TopicKind::raw: return lcm_json_schema(spec.type_name);
    case TopicKind::terrain_grid:
    case TopicKind::traverse_grid: return grid();
    case TopicKind::laser_scan: return laser_scan();
    case TopicKind::point_cloud: return point_cloud();
    case TopicKind::pose_transform:
    case TopicKind::laser_transform: return frame_transform();
    case TopicKind::pose_in_frame: return pose_in_frame();
    case TopicKind::location_fix: return location_fix();
    case TopicKind::arcs_scene: return scene_update();
    case TopicKind::status_log: return log();
    }
    return {};
}

}  // namespace ugv::foxglove
