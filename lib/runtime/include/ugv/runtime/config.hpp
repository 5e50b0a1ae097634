// Daemon configuration from one TOML file, validated at start-up.
//
// Every getter records the key as known and its effective value; finish() then rejects any
// key in the file that no getter asked for. Any problem throws ConfigError, whose what() is
// the one line `FILE: KEY: why` that the daemon prints before exiting with status 2.
//
//   ugv::runtime::Config cfg = ugv::runtime::Config::load(path);
//   auto device = cfg.get_string("device", "/dev/ttyUSB0");
//   auto baud = cfg.get_int("baud", 500000, {9600, 19200, 38400, 500000});
//   auto height = cfg.get_double("sensor_height_m", 0.87, 0.0, 5.0);
//   auto out = cfg.get_channel("channel", "LMS_SCAN");            // a name to publish on
//   auto in = cfg.get_channel_regex("points_channel", "POINTS.*"); // a pattern to subscribe with
//   auto sensor = cfg.section("mount");   // a [mount] table, same rules inside
//   for (auto& box : cfg.tables("box")) { ...; box.finish(); }   // [[box]] tables
//   cfg.finish();
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ugv::runtime {

class ConfigError : public std::runtime_error
{
public:
    ConfigError(const std::string& file, const std::string& key, const std::string& why);
    const std::string& file() const { return file_; }
    const std::string& key() const { return key_; }
    const std::string& why() const { return why_; }

private:
    std::string file_, key_, why_;
};

class Config
{
public:
    // The largest config file load() reads; a larger one is refused unread.
    static constexpr std::size_t kMaxFileBytes = 1 << 20;
    // Reads and parses path. Throws ConfigError (key "-") for anything but a readable regular
    // file of at most kMaxFileBytes (a directory, FIFO, device or socket is refused without
    // being opened, so a FIFO cannot block) and for a TOML syntax error (line and column in why).
    static Config load(const std::string& path);
    // Parses text as if read from a file called name (for tests and built-in defaults).
    static Config parse(const std::string& text, const std::string& name = "<string>");
    // An empty configuration: every getter returns its default.
    static Config empty(const std::string& name = "<defaults>");

    Config(Config&&) noexcept;
    Config& operator=(Config&&) noexcept;
    ~Config();

    std::string get_string(const std::string& key, const std::string& def);
    // One of allowed (exact match).
    std::string get_enum(const std::string& key, const std::string& def, std::initializer_list<const char*> allowed);
    bool get_bool(const std::string& key, bool def);
    // Inclusive range [min, max].
    int64_t get_int(const std::string& key, int64_t def, int64_t min, int64_t max);
    // One of allowed.
    int64_t get_int(const std::string& key, int64_t def, std::initializer_list<int64_t> allowed);
    // Inclusive range; integers in the file are accepted as doubles; NaN/Inf refused.
    double get_double(const std::string& key, double def, double min, double max);
    // An array of numbers of exactly n elements (n = 0: any length), each in [min, max].
    std::vector<double> get_doubles(const std::string& key, const std::vector<double>& def, std::size_t n,
                                    double min, double max);
    std::vector<std::string> get_strings(const std::string& key, const std::vector<std::string>& def);
    // An LCM channel to publish on: 1..kMaxChannelChars of letters, digits, '_', '-' and '.'
    // (no other regex character: subscribers match names with regexes).
    std::string get_channel(const std::string& key, const std::string& def);
    // An LCM channel regex to subscribe with: 1..kMaxChannelRegexChars printable characters, no
    // {n,m} repetition, compiling both as the live bus (anchored POSIX extended) and the log
    // replay (std::regex) use it.
    std::string get_channel_regex(const std::string& key, const std::string& def);
    // LCM's limit on a channel name (LCM_MAX_CHANNEL_NAME_LENGTH): liblcm refuses to publish
    // on a longer one.
    static constexpr std::size_t kMaxChannelChars = 63;
    static constexpr std::size_t kMaxChannelRegexChars = 255;
    // Why name is not a channel to publish on, or empty when it is one.
    static std::string channel_name_problem(const std::string& name);
    // Why pattern is not a channel regex to subscribe with, or empty when it is one.
    static std::string channel_regex_problem(const std::string& pattern);
    bool has(const std::string& key) const;
    // True when key holds an array of tables ([[key]]): for a key that may be either a
    // table or an array of tables (a scenario's [laser] or [[laser]]).
    bool has_tables(const std::string& key) const;
    // A sub-table [name]; its keys are reported as "name.key". Missing table = all defaults.
    Config section(const std::string& name);
    // An array of tables ([[name]] ... [[name]]), in file order; keys inside are reported as
    // "name[i].key". Missing = empty. Call finish() on each element: it checks that element's
    // keys (the parent's finish() leaves them to it).
    std::vector<Config> tables(const std::string& name);
    // Throws for a value found invalid by the caller, in the same one-line form.
    [[noreturn]] void fail(const std::string& key, const std::string& why) const;

    // Throws ConfigError for the first key in the file that no getter asked for.
    void finish();
    // The effective configuration (defaults filled in) as TOML, for --print-config.
    std::string effective_toml() const;
    const std::string& file() const;

private:
    struct Impl;
    explicit Config(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace ugv::runtime
