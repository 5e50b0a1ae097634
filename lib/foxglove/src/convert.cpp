// topics_for() and Converter: each ugv type onto its Foxglove topics, each message as JSON.
#include <bit>
#include <cmath>
#include <cstring>

#include "json_out.hpp"
#include "ugv/candidate_arcs_t.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/foxglove/topics.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/reflect.hpp"
#include "ugv/reflect_message.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"

static_assert(std::endian::native == std::endian::little, "Foxglove's packed fields are little-endian");

namespace ugv::foxglove {
namespace {

using detail::JsonOut;

// NumericType of foxglove.PackedElementField.
enum NumericType : int { int8 = 2, int32 = 6, float32 = 7 };

struct Packed
{
    const char* name;
    uint32_t offset;
    int type;
};

template <typename Msg>
bool decode(const uint8_t* data, std::size_t size, Msg& msg)
{
    if (!reflect::well_formed(data, size) || size > static_cast<std::size_t>(INT32_MAX)) return false;
    return msg.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
}

void put_f32(uint8_t* at, float v) { std::memcpy(at, &v, 4); }

// The cells of an nx x ny map (cell (i, j) at i * ny + j) in Foxglove's order: row j (along
// y), column i (along x), into cells (its capacity reused). fill(cell bytes, k) writes map cell k.
template <typename Fill>
void grid_cells(int nx, int ny, uint32_t stride, std::vector<uint8_t>& cells, Fill fill)
{
    const auto x = static_cast<std::size_t>(nx), y = static_cast<std::size_t>(ny);
    cells.assign(x * y * stride, 0);  // the padding bytes stay 0
    for (std::size_t i = 0; i < x; ++i)
        for (std::size_t j = 0; j < y; ++j) fill(cells.data() + (j * x + i) * stride, i * y + j);
}

void fields(JsonOut& j, std::initializer_list<Packed> list)
{
    j.key("fields").begin_array();
    for (const auto& f : list)
        j.begin_object().key("name").string(f.name).key("offset").integer(f.offset).key("type").integer(f.type).end_object();
    j.end_array();
}

void identity_pose(JsonOut& j)
{
    j.key("pose").begin_object().vec3("position", 0, 0, 0).quat("orientation", 1, 0, 0, 0).end_object();
}

// The grid's pose in the world frame: the map's corner cell (0, 0) on the ground under the
// body origin, its axes the body's turned by -residual_yaw about up (docs/terrain.md).
void grid_header(JsonOut& j, const ugv::pose_t& pose, float residual_yaw, float origin_x, float origin_y, int nx,
                 float resolution, uint32_t cell_stride)
{
    const double yaw = pose.yaw - residual_yaw;
    const double c = std::cos(yaw), s = std::sin(yaw);
    j.key("timestamp").time_us(pose.utime).key("frame_id").string(kWorldFrame);
    j.key("pose").begin_object();
    j.vec3("position", pose.position[0] + c * origin_x - s * origin_y, pose.position[1] + s * origin_x + c * origin_y,
           pose.position[2]);
    j.quat("orientation", std::cos(yaw / 2), 0, 0, std::sin(yaw / 2));
    j.end_object();
    // Foxglove's rows run along the grid's y, columns along x; ours are i (x) major.
    j.key("column_count").integer(nx);
    j.key("cell_size").begin_object().key("x").number(resolution).key("y").number(resolution).end_object();
    j.key("row_stride").integer(static_cast<int64_t>(nx) * cell_stride).key("cell_stride").integer(cell_stride);
}

void terrain_grid(const ugv::terrain_map_t& m, std::vector<uint8_t>& cells, std::string& json)
{
    constexpr uint32_t stride = 24;
    grid_cells(m.nx, m.ny, stride, cells, [&](uint8_t* at, std::size_t k) {
        put_f32(at, m.mean_z[k]);
        put_f32(at + 4, m.variance_z[k]);
        std::memcpy(at + 8, &m.count[k], 4);
        put_f32(at + 12, m.max_z[k]);
        put_f32(at + 16, m.min_z[k]);
        put_f32(at + 20, m.age_s[k]);
    });
    JsonOut j(json);
    j.begin_object();
    grid_header(j, m.pose, m.residual_yaw, m.origin_x, m.origin_y, m.nx, m.resolution, stride);
    fields(j, {{"height", 0, float32}, {"variance", 4, float32}, {"count", 8, int32}, {"max", 12, float32},
               {"min", 16, float32}, {"age", 20, float32}});
    j.key("data").base64(cells.data(), cells.size());
    j.end_object();
}

void traverse_grid(const ugv::traversability_map_t& m, std::vector<uint8_t>& cells, std::string& json)
{
    constexpr uint32_t stride = 32;  // 7 floats, the class byte, 3 bytes of padding
    grid_cells(m.nx, m.ny, stride, cells, [&](uint8_t* at, std::size_t k) {
        put_f32(at, m.cost[k]);
        put_f32(at + 4, m.step_m[k]);
        put_f32(at + 8, m.drop_m[k]);
        put_f32(at + 12, m.slope_deg[k]);
        put_f32(at + 16, m.roughness_m[k]);
        put_f32(at + 20, m.span_m[k]);
        put_f32(at + 24, m.certainty[k]);
        std::memcpy(at + 28, &m.cell_class[k], 1);
    });
    JsonOut j(json);
    j.begin_object();
    grid_header(j, m.pose, m.residual_yaw, m.origin_x, m.origin_y, m.nx, m.resolution, stride);
    fields(j, {{"cost", 0, float32}, {"step", 4, float32}, {"drop", 8, float32}, {"slope_deg", 12, float32},
               {"roughness", 16, float32}, {"span", 20, float32}, {"certainty", 24, float32}, {"class", 28, int8}});
    j.key("data").base64(cells.data(), cells.size());
    j.end_object();
}

template <typename Map>
bool map_fits(const Map& m)
{
    return m.nx > 0 && m.ny > 0 && static_cast<int64_t>(m.nx) * m.ny == m.ncells;
}

bool laser_scan(const uint8_t* data, std::size_t size, std::string& json)
{
    ugv::laser_scan_t m{};
    if (!decode(data, size, m)) return false;
    JsonOut j(json);
    j.begin_object().key("timestamp").time_us(m.utime).key("frame_id").string(kLaserFrame);
    identity_pose(j);
    const double last = m.nranges > 0 ? m.angle_min + (m.nranges - 1) * static_cast<double>(m.angle_increment) : m.angle_min;
    j.key("start_angle").number(m.angle_min).key("end_angle").number(last);
    // No return (NaN) has no JSON number: 0, which Foxglove draws at the origin, not in the scene.
    j.key("ranges").begin_array();
    for (const float r : m.ranges) j.number(r, 0);
    j.end_array().key("intensities").begin_array().end_array().end_object();
    return true;
}

bool point_cloud(const uint8_t* data, std::size_t size, std::string& json, double origin[3])
{
    ugv::point_cloud_t m{};
    if (!decode(data, size, m)) return false;
    for (int k = 0; k < 3; ++k) origin[k] = m.sensor_origin[k];
    constexpr uint32_t stride = 24;
    const auto n = static_cast<std::size_t>(m.npoints);
    std::vector<uint8_t> points(n * stride);
    for (std::size_t k = 0; k < n; ++k) {
        uint8_t* at = points.data() + k * stride;
        put_f32(at, m.x[k]);
        put_f32(at + 4, m.y[k]);
        put_f32(at + 8, m.z[k]);
        put_f32(at + 12, m.range[k]);
        put_f32(at + 16, m.variance[k]);
        put_f32(at + 20, m.time_offset[k]);
    }
    JsonOut j(json);
    j.begin_object().key("timestamp").time_us(m.utime).key("frame_id").string(kBodyFrame);
    identity_pose(j);
    j.key("point_stride").integer(stride);
    fields(j, {{"x", 0, float32}, {"y", 4, float32}, {"z", 8, float32}, {"range", 12, float32},
               {"variance", 16, float32}, {"time_offset", 20, float32}});
    j.key("data").base64(points.data(), points.size()).end_object();
    return true;
}

void transform(JsonOut& j, int64_t utime, const char* parent, const char* child, const double t[3], double w, double x,
               double y, double z)
{
    j.begin_object().key("timestamp").time_us(utime);
    j.key("parent_frame_id").string(parent).key("child_frame_id").string(child);
    j.vec3("translation", t[0], t[1], t[2]).quat("rotation", w, x, y, z).end_object();
}

bool pose_message(const uint8_t* data, std::size_t size, std::string& json, bool as_transform)
{
    ugv::pose_t m{};
    if (!decode(data, size, m)) return false;
    const double* q = m.orientation;
    JsonOut j(json);
    if (as_transform) {
        transform(j, m.utime, kWorldFrame, kBodyFrame, m.position, q[0], q[1], q[2], q[3]);
        return true;
    }
    j.begin_object().key("timestamp").time_us(m.utime).key("frame_id").string(kWorldFrame);
    j.key("pose").begin_object().vec3("position", m.position[0], m.position[1], m.position[2]);
    j.quat("orientation", q[0], q[1], q[2], q[3]).end_object().end_object();
    return true;
}

bool laser_transform(const uint8_t* data, std::size_t size, std::string& json, const double origin[3])
{
    ugv::servo_state_t m{};
    if (!decode(data, size, m)) return false;
    // Tilt positive = nose down: a rotation about body +Y by +angle turns +X towards -Z.
    const double a = std::isfinite(m.angle) ? m.angle : 0;
    JsonOut j(json);
    transform(j, m.utime, kBodyFrame, kLaserFrame, origin, std::cos(a / 2), 0, std::sin(a / 2), 0);
    return true;
}

bool location_fix(const uint8_t* data, std::size_t size, std::string& json)
{
    ugv::gps_fix_t m{};
    if (!decode(data, size, m)) return false;
    const double e = m.sigma_longitude, n = m.sigma_latitude, u = m.sigma_height;
    const bool known = std::isfinite(e) && std::isfinite(n) && std::isfinite(u);
    JsonOut j(json);
    j.begin_object().key("timestamp").time_us(m.utime).key("frame_id").string(kBodyFrame);
    j.key("latitude").number(m.latitude).key("longitude").number(m.longitude).key("altitude").number(m.height);
    // Covariance about the fix, ENU row-major: the receiver's sigmas on the diagonal.
    j.key("position_covariance").begin_array();
    const double diag[3] = {e * e, n * n, u * u};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) j.number(known && r == c ? diag[r] : 0.0);
    j.end_array().key("position_covariance_type").integer(known ? 2 : 0).end_object();
    return true;
}

void color(JsonOut& j, double r, double g, double b)
{
    j.key("color").begin_object().key("r").number(r).key("g").number(g).key("b").number(b).key("a").number(1).end_object();
}

bool arcs_scene(std::string_view channel, const uint8_t* data, std::size_t size, std::string& json)
{
    ugv::candidate_arcs_t m{};
    if (!decode(data, size, m)) return false;
    const double yaw = m.pose.yaw;
    JsonOut j(json);
    j.begin_object().key("deletions").begin_array().end_array().key("entities").begin_array().begin_object();
    j.key("timestamp").time_us(m.utime).key("frame_id").string(kWorldFrame).key("id").string(channel);
    j.key("lifetime").begin_object().key("sec").integer(0).key("nsec").integer(0).end_object();
    j.key("frame_locked").boolean(false).key("metadata").begin_array().end_array();
    for (const char* empty : {"arrows", "cubes", "spheres", "cylinders"}) j.key(empty).begin_array().end_array();
    j.key("lines").begin_array();
    const std::size_t n = static_cast<std::size_t>(m.narcs);
    const double length = std::isfinite(m.length_m) && m.length_m > 0 ? m.length_m : 0;
    for (std::size_t k = 0; k < n; ++k) {
        j.begin_object().key("type").integer(0);  // LINE_STRIP
        // The arc starts at the body origin on the ground, along the map pose's heading.
        j.key("pose").begin_object().vec3("position", m.pose.position[0], m.pose.position[1], m.pose.position[2]);
        j.quat("orientation", std::cos(yaw / 2), 0, 0, std::sin(yaw / 2)).end_object();
        j.key("thickness").number(static_cast<int>(k) == m.best ? 0.08 : 0.04).key("scale_invariant").boolean(false);
        j.key("points").begin_array();
        const double kappa = m.curvature[k];
        constexpr int steps = 20;
        for (int s = 0; s <= steps; ++s) {
            const double d = length * s / steps;
            const bool straight = std::abs(kappa) < 1e-6;
            const double x = straight ? d : std::sin(kappa * d) / kappa;
            const double y = straight ? 0 : (1 - std::cos(kappa * d)) / kappa;
            j.begin_object().key("x").number(x).key("y").number(y).key("z").number(0).end_object();
        }
        j.end_array();
        if (static_cast<int>(k) == m.best) color(j, 0.1, 0.9, 0.1);
        else if (m.blocked[k]) color(j, 0.9, 0.1, 0.1);
        else color(j, 0.9, 0.8, 0.2);
        j.key("colors").begin_array().end_array().key("indices").begin_array().end_array().end_object();
    }
    j.end_array();
    for (const char* empty : {"triangles", "texts", "models"}) j.key(empty).begin_array().end_array();
    j.end_object().end_array().end_object();
    return true;
}

const char* state_name(int state)
{
    switch (state) {
    case ugv::daemon_status_t::STATE_STARTING: return "STARTING";
    case ugv::daemon_status_t::STATE_RUNNING: return "RUNNING";
    case ugv::daemon_status_t::STATE_DEGRADED: return "DEGRADED";
    case ugv::daemon_status_t::STATE_FAULT: return "FAULT";
    case ugv::daemon_status_t::STATE_STOPPING: return "STOPPING";
    default: return "UNKNOWN";
    }
}

int log_level(int state)
{
    switch (state) {
    case ugv::daemon_status_t::STATE_DEGRADED: return 3;  // WARNING
    case ugv::daemon_status_t::STATE_FAULT: return 4;     // ERROR
    case ugv::daemon_status_t::STATE_STARTING:
    case ugv::daemon_status_t::STATE_RUNNING:
    case ugv::daemon_status_t::STATE_STOPPING: return 2;  // INFO
    default: return 0;
    }
}

}  // namespace

// The maps of the last message, decoded once for its raw and its grid topic; their arrays'
// capacity is kept from message to message.
struct Converter::Decoded
{
    enum class Holds { nothing, terrain, traverse };
    Holds holds = Holds::nothing;
    ugv::terrain_map_t terrain{};
    ugv::traversability_map_t traverse{};
    std::vector<uint8_t> cells;  // a grid's cells before base64

    template <typename Map>
    const Map* get(Map& m, Holds kind, const uint8_t* data, std::size_t size, bool same_message)
    {
        if (same_message && holds == kind) return &m;
        holds = Holds::nothing;
        if (!decode(data, size, m)) return nullptr;
        holds = kind;
        return &m;
    }
    const ugv::terrain_map_t* terrain_map(const uint8_t* data, std::size_t size, bool same)
    {
        return get(terrain, Holds::terrain, data, size, same);
    }
    const ugv::traversability_map_t* traverse_map(const uint8_t* data, std::size_t size, bool same)
    {
        return get(traverse, Holds::traverse, data, size, same);
    }
};

Converter::Converter() : decoded_(std::make_unique<Decoded>()) {}
Converter::~Converter() = default;

std::vector<TopicSpec> topics_for(std::string_view channel, std::string_view type_name, bool with_raw)
{
    if (!reflect::fields_of(type_name)) return {};
    const std::string ch(channel), type(type_name);
    std::vector<TopicSpec> out;
    if (with_raw) out.push_back({ch, type, type, TopicKind::raw});
    auto add = [&](const char* suffix, const char* schema, TopicKind kind) {
        out.push_back({ch + "/" + suffix, schema, type, kind});
    };
    if (type == "ugv.terrain_map_t") add("grid", "foxglove.Grid", TopicKind::terrain_grid);
    else if (type == "ugv.traversability_map_t") add("grid", "foxglove.Grid", TopicKind::traverse_grid);
    else if (type == "ugv.laser_scan_t") add("scan", "foxglove.LaserScan", TopicKind::laser_scan);
    else if (type == "ugv.point_cloud_t") add("cloud", "foxglove.PointCloud", TopicKind::point_cloud);
    else if (type == "ugv.pose_t") {
        add("tf", "foxglove.FrameTransform", TopicKind::pose_transform);
        add("pose", "foxglove.PoseInFrame", TopicKind::pose_in_frame);
    } else if (type == "ugv.servo_state_t") add("tf", "foxglove.FrameTransform", TopicKind::laser_transform);
    else if (type == "ugv.gps_fix_t") add("fix", "foxglove.LocationFix", TopicKind::location_fix);
    else if (type == "ugv.candidate_arcs_t") add("scene", "foxglove.SceneUpdate", TopicKind::arcs_scene);
    else if (type == "ugv.daemon_status_t") add("log", "foxglove.Log", TopicKind::status_log);
    return out;
}

bool Converter::convert(const TopicSpec& spec, const uint8_t* data, std::size_t size, std::string& json,
                        bool same_message)
{
    bool ok = false;
    Decoded& d = *decoded_;
    if (!same_message) d.holds = Decoded::Holds::nothing;  // a new message: whatever it held is stale
    switch (spec.kind) {
    case TopicKind::raw: {
        // A map's JSON from the decode its grid uses too; other types through the reflection.
        if (spec.type_name == "ugv.terrain_map_t" && reflect::type_name_of(data, size) == spec.type_name) {
            const auto* m = d.terrain_map(data, size, same_message);
            if ((ok = m != nullptr)) reflect::message_json(*m, json);
        } else if (spec.type_name == "ugv.traversability_map_t" && reflect::type_name_of(data, size) == spec.type_name) {
            const auto* m = d.traverse_map(data, size, same_message);
            if ((ok = m != nullptr)) reflect::message_json(*m, json);
        } else {
            std::string type;
            ok = reflect::to_json(data, size, type, json) == reflect::DecodeResult::ok && type == spec.type_name;
        }
        break;
    }
    case TopicKind::terrain_grid:
        if (const auto* m = d.terrain_map(data, size, same_message); m && map_fits(*m)) {
            terrain_grid(*m, d.cells, json);
            ok = true;
        }
        break;
    case TopicKind::traverse_grid:
        if (const auto* m = d.traverse_map(data, size, same_message); m && map_fits(*m)) {
            traverse_grid(*m, d.cells, json);
            ok = true;
        }
        break;
    case TopicKind::laser_scan: ok = laser_scan(data, size, json); break;
    case TopicKind::point_cloud: ok = point_cloud(data, size, json, laser_origin_); break;
    case TopicKind::pose_transform: ok = pose_message(data, size, json, true); break;
    case TopicKind::pose_in_frame: ok = pose_message(data, size, json, false); break;
    case TopicKind::laser_transform: ok = laser_transform(data, size, json, laser_origin_); break;
    case TopicKind::location_fix: ok = location_fix(data, size, json); break;
    case TopicKind::arcs_scene: {
        const std::string_view channel = std::string_view(spec.topic).substr(0, spec.topic.rfind('/'));
        ok = arcs_scene(channel, data, size, json);
        break;
    }
    case TopicKind::status_log: {
        ugv::daemon_status_t m{};
        if (!decode(data, size, m)) break;
        ok = true;
        auto it = status_.find(spec.topic);
        if (it == status_.end()) it = status_.emplace(spec.topic, StatusSeen{}).first;
        if (it->second.state == m.state && it->second.last_error == m.last_error) {
            ++counters_.unchanged;
            return false;
        }
        it->second = {m.state, m.last_error};
        std::string text = state_name(m.state);
        if (!m.last_error.empty()) text += ": " + m.last_error;
        JsonOut j(json);
        j.begin_object().key("timestamp").time_us(m.utime).key("level").integer(log_level(m.state));
        j.key("message").string(text).key("name").string(m.instance.empty() ? m.name : m.name + "@" + m.instance);
        j.key("file").string("").key("line").integer(0).end_object();
        break;
    }
    }
    if (!ok) {
        ++counters_.malformed;
        return false;
    }
    ++counters_.converted;
    return true;
}

}  // namespace ugv::foxglove
