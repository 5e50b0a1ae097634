#include "ugv/novatel/encoding.hpp"

#include <cctype>
#include <cmath>
#include <cstring>

#include "body_fields.hpp"
#include "body_layout.hpp"
#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/text_fields.hpp"

namespace ugv::novatel {
namespace {

// NMEA angle: ddmm.mmmmmmm with the hemisphere letter.
std::string nmea_angle(double deg, bool latitude)
{
    if (!std::isfinite(deg)) {
        return ",";
    }
    const double a = std::fabs(deg);
    const double whole = std::floor(a);
    const double minutes = (a - whole) * 60.0;
    const char hemisphere = latitude ? (deg < 0 ? 'S' : 'N') : (deg < 0 ? 'W' : 'E');
    return latitude ? format("%02d%010.7f,%c", static_cast<int>(whole), minutes, hemisphere)
                    : format("%03d%010.7f,%c", static_cast<int>(whole), minutes, hemisphere);
}

std::string nmea_time(double s)
{
    if (!std::isfinite(s)) {
        return "";
    }
    const int hours = static_cast<int>(s / 3600.0);
    const int minutes = static_cast<int>((s - hours * 3600.0) / 60.0);
    const double seconds = s - hours * 3600.0 - minutes * 60.0;
    return format("%02d%02d%05.2f", hours, minutes, seconds);
}

std::string opt(double v, const char* fmt)
{
    return std::isfinite(v) ? format(fmt, v) : std::string();
}

std::string upper(std::string_view s)
{
    std::string out(s);
    for (auto& c : out) {
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return out;
}

}  // namespace

std::vector<uint8_t> encode_binary(const LogHeader& h, const std::vector<uint8_t>& body)
{
    constexpr std::size_t kHeader = 28;
    std::vector<uint8_t> f(kHeader + body.size() + 4, 0);
    f[0] = 0xAA;
    f[1] = 0x44;
    f[2] = 0x12;
    f[3] = kHeader;
    put<uint16_t>(f, 4, h.id);
    f[6] = h.response ? 0x80 : 0x00;
    f[7] = 0x20;  // COM1
    put<uint16_t>(f, 8, static_cast<uint16_t>(body.size()));
    put<uint16_t>(f, 10, h.sequence);
    f[12] = std::isfinite(h.idle_percent) ? static_cast<uint8_t>(std::lround(h.idle_percent * 2)) : 0;
    f[13] = static_cast<uint8_t>(h.time_status);
    put<uint16_t>(f, 14, static_cast<uint16_t>(h.week));
    put<uint32_t>(f, 16, h.ms);
    put<uint32_t>(f, 20, h.receiver_status);
    put<uint16_t>(f, 26, h.software_build);
    std::memcpy(f.data() + kHeader, body.data(), body.size());
    put<uint32_t>(f, kHeader + body.size(), crc32(f.data(), kHeader + body.size()));
    return f;
}

std::vector<uint8_t> encode_body(const LogInfo& log, const Message& m) { return log.layout->to_binary(m); }

std::vector<uint8_t> encode_position_body(const Position& p) { return position_layout.to_binary(p); }

std::vector<uint8_t> encode_velocity_body(const Velocity& v) { return velocity_layout.to_binary(v); }

std::string encode_ascii(std::string_view name, const LogHeader& h, std::string_view fields)
{
    std::string text = std::string(name) +
                       format(",COM1,%u,%.1f,%s,%u,%.3f,%08x,0000,%u;", static_cast<unsigned>(h.sequence),
                              std::isfinite(h.idle_percent) ? h.idle_percent : 0.0,
                              enum_name(time_status_name(h.time_status), h.time_status).c_str(), h.week,
                              h.ms / 1000.0, h.receiver_status, static_cast<unsigned>(h.software_build)) +
                       std::string(fields);
    const uint32_t crc = crc32(reinterpret_cast<const uint8_t*>(text.data()), text.size());
    return "#" + text + format("*%08x\r\n", crc);
}

std::string encode_fields(const LogInfo& log, const Message& m) { return log.layout->to_ascii(m); }

std::string position_fields(const Position& p) { return position_layout.to_ascii(p); }

std::string velocity_fields(const Velocity& v) { return velocity_layout.to_ascii(v); }

std::string encode_nmea(std::string_view body)
{
    const uint8_t x = nmea_checksum(reinterpret_cast<const uint8_t*>(body.data()), body.size());
    return "$" + std::string(body) + format("*%02X\r\n", static_cast<unsigned>(x));
}

std::string gga_body(const Gga& g)
{
    const bool fix = g.quality > 0;
    return g.talker + "GGA," + nmea_time(g.utc_time_s) + "," + (fix ? nmea_angle(g.latitude_deg, true) : ",") +
           "," + (fix ? nmea_angle(g.longitude_deg, false) : ",") + format(",%d,", g.quality) +
           (g.satellites_used >= 0 ? format("%02d", g.satellites_used) : "") + "," + opt(g.hdop, "%.1f") + "," +
           opt(g.altitude_msl_m, "%.3f") + (fix ? ",M," : ",,") + opt(g.undulation_m, "%.2f") +
           (fix ? ",M," : ",,") + opt(g.differential_age_s, "%.1f") + "," + g.station_id;
}

std::string rmc_body(const Rmc& r)
{
    const std::string date =
        r.year > 0 ? format("%02d%02d%02d", r.day, r.month, r.year % 100) : std::string();
    return r.talker + "RMC," + nmea_time(r.utc_time_s) + (r.valid ? ",A," : ",V,") +
           nmea_angle(r.latitude_deg, true) + "," + nmea_angle(r.longitude_deg, false) + "," +
           opt(r.speed_mps * 3600.0 / 1852.0, "%.3f") + "," + opt(r.track_deg, "%.1f") + "," + date + ",0.0,E";
}

std::string gst_body(const Gst& g)
{
    return g.talker + "GST," + nmea_time(g.utc_time_s) + "," + opt(g.rms_m, "%.3f") + "," +
           opt(g.semi_major_m, "%.3f") + "," + opt(g.semi_minor_m, "%.3f") + "," + opt(g.orientation_deg, "%.1f") +
           "," + opt(g.sigma_latitude_m, "%.3f") + "," + opt(g.sigma_longitude_m, "%.3f") + "," +
           opt(g.sigma_altitude_m, "%.3f");
}

std::string unlogall_command() { return "UNLOGALL\r\n"; }

std::string log_command(std::string_view message, double period_s)
{
    return "LOG " + upper(message) + format(" ONTIME %g\r\n", period_s);
}

std::string com_command(int baud) { return format("COM %d\r\n", baud); }

Command parse_command(std::string_view line)
{
    // Split on spaces (and commas, which NovAtel also accepts); drop CR/LF.
    std::vector<std::string> words;
    std::string word;
    for (const char c : line) {
        if (c == ' ' || c == ',' || c == '\t' || c == '\r' || c == '\n') {
            if (!word.empty()) {
                words.push_back(upper(word));
                word.clear();
            }
        } else {
            word += c;
        }
    }
    if (!word.empty()) {
        words.push_back(upper(word));
    }
    Command cmd;
    if (words.empty()) {
        return cmd;
    }
    const auto is_port = [](const std::string& w) {
        return w.rfind("COM", 0) == 0 || w.rfind("USB", 0) == 0 || w == "THISPORT";
    };
    std::size_t i = 1;
    if (words[0] == "UNLOGALL") {
        cmd.type = Command::Type::unlogall;
    } else if (words[0] == "LOG") {
        if (i < words.size() && is_port(words[i])) {
            ++i;
        }
        if (i >= words.size()) {
            return cmd;
        }
        cmd.type = Command::Type::log;
        cmd.message = words[i++];
        cmd.trigger = i < words.size() ? words[i++] : "ONCE";
        if (i < words.size()) {
            parse_double(words[i], cmd.period_s);
        }
    } else if (words[0] == "COM") {
        if (i < words.size() && is_port(words[i]) && words[i] != "COM") {
            ++i;
        }
        int64_t baud = 0;
        if (i < words.size() && parse_int(words[i], baud) && baud > 0 && baud <= 921600) {
            cmd.type = Command::Type::com;
            cmd.baud = static_cast<int>(baud);
        }
    }
    return cmd;
}

}  // namespace ugv::novatel
