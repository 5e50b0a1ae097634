#include "ugv/runtime/config.hpp"

#include <regex.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <regex>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "ugv/io/whole_file.hpp"

namespace ugv::runtime {

ConfigError::ConfigError(const std::string& file, const std::string& key, const std::string& why)
    : std::runtime_error(file + ": " + key + ": " + why), file_(file), key_(key), why_(why)
{
}

// The table being read, the keys the program asked for, and the effective values (for
// --print-config). A section shares its parent's effective table, under its own name.
struct Config::Impl
{
    std::string file;
    std::string prefix;  // "mount." inside [mount]
    toml::table table;
    std::set<std::string> known;
    std::shared_ptr<toml::table> effective;  // the root's; sections write into a sub-table
    toml::table* effective_here = nullptr;
};

namespace {

std::string type_name(const toml::node& n)
{
    switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date/time";
    }
}

std::string fmt_double(double d)
{
    std::ostringstream s;
    s << d;
    return s.str();
}

// Printable, and a character a channel name or pattern may hold in the journal's one line.
bool printable(char c) { return c > ' ' && c < 0x7f; }

constexpr int kMaxGroupDepth = 4;

// Why a regex's structure could make its compilation explode or mean something else to
// one of the compilers, or empty. Bracket
// expressions ([...], where '(' and '+' are plain characters) and escapes are skipped.
std::string nesting_problem(const std::string& re)
{
    int depth = 0;
    bool after_quantifier = false;
    for (std::size_t i = 0; i < re.size(); ++i) {
        const char c = re[i];
        if (c == '\\') {
            // An escape takes the next character literally; \1, \d and the like mean
            // different things (or overflow: \3333333333333333333) in the two compilers.
            if (++i < re.size() && std::isalnum(static_cast<unsigned char>(re[i])))
                return "an escape in a channel regex is for punctuation only (\\., \\*), not \\" + std::string(1, re[i]);
            after_quantifier = false;
        } else if (c == '[') {
            std::size_t j = i + 1;
            if (j < re.size() && re[j] == '^') ++j;
            if (j < re.size() && re[j] == ']') ++j;  // a leading ']' is a member
            while (j < re.size() && re[j] != ']') ++j;
            i = j;
            after_quantifier = false;
        } else if (c == '*' || c == '+' || c == '?') {
            if (after_quantifier) return "no quantifier on a quantifier in a channel regex";
            after_quantifier = true;
        } else {
            after_quantifier = false;
            if (c == '(' && ++depth > kMaxGroupDepth)
                return "groups nested more than " + std::to_string(kMaxGroupDepth) + " deep in a channel regex";
            if (c == ')') --depth;
        }
    }
    return {};
}

}  // namespace

std::string Config::channel_name_problem(const std::string& name)
{
    if (name.empty()) return "must not be empty";
    if (name.size() > kMaxChannelChars)
        return "is " + std::to_string(name.size()) + " characters, more than LCM's " + std::to_string(kMaxChannelChars);
    for (const char c : name)
        if (!printable(c)) return "a channel name is letters, digits, '_', '-' and '.' (found a space or control character)";
    for (const char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (!(std::isalnum(u) || c == '_' || c == '-' || c == '.'))
            return "'" + name + "' is not a channel name (letters, digits, '_', '-', '.')";
    }
    return {};
}

std::string Config::channel_regex_problem(const std::string& pattern)
{
    if (pattern.empty()) return "must not be empty";
    if (pattern.size() > kMaxChannelRegexChars)
        return "is " + std::to_string(pattern.size()) + " characters, more than the " +
               std::to_string(kMaxChannelRegexChars) + " a channel regex may have";
    for (const char c : pattern)
        if (!printable(c)) return "a channel regex is printable characters without spaces";
    // glibc's regcomp expands repetitions by copying what they repeat: a{999}{999}, 24
    // stacked '+' or 20 nested (...)+ take gigabytes. Channel patterns need none of that:
    // no {n,m}, no quantifier on a quantifier, groups nested at most kMaxGroupDepth deep.
    if (pattern.find_first_of("{}") != std::string::npos) return "'" + pattern + "': no {n,m} in a channel regex";
    if (const std::string why = nesting_problem(pattern); !why.empty()) return "'" + pattern + "': " + why;
    const std::string anchored = "^" + pattern + "$";  // as the live bus and liblcm match it
    regex_t re{};
    const int rc = regcomp(&re, anchored.c_str(), REG_EXTENDED | REG_NOSUB);
    if (rc != 0) {
        char why[128];
        regerror(rc, &re, why, sizeof why);
        return "'" + pattern + "' is not a regex: " + why;
    }
    regfree(&re);
    try {
        std::regex check(pattern);  // the log replay's matching
    } catch (const std::exception& e) {  // regex_error; any other failure refuses it as well
        return "'" + pattern + "' is not a regex: " + e.what();
    }
    return {};
}

Config::Config(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Config::Config(Config&&) noexcept = default;
Config& Config::operator=(Config&&) noexcept = default;
Config::~Config() = default;

Config Config::parse(const std::string& text, const std::string& name)
{
    auto impl = std::make_unique<Impl>();
    impl->file = name;
    try {
        impl->table = toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        const auto& where = e.source().begin;
        throw ConfigError(name, "-", std::string(e.description()) + " (line " + std::to_string(where.line) +
                                         ", column " + std::to_string(where.column) + ")");
    }
    impl->effective = std::make_shared<toml::table>();
    impl->effective_here = impl->effective.get();
    return Config(std::move(impl));
}

Config Config::load(const std::string& path)
{
    std::vector<uint8_t> bytes;
    std::string why;
    switch (io::read_regular_file(path, kMaxFileBytes, bytes, why)) {
    case io::ReadResult::ok: break;
    case io::ReadResult::missing:
    case io::ReadResult::unreadable: throw ConfigError(path, "-", "cannot read the file: " + why);
    case io::ReadResult::not_a_file: throw ConfigError(path, "-", why);
    case io::ReadResult::too_large: throw ConfigError(path, "-", why + " (the most a config file may have)");
    }
    return parse(std::string(bytes.begin(), bytes.end()), path);
}

Config Config::empty(const std::string& name) { return parse("", name); }

const std::string& Config::file() const { return impl_->file; }

bool Config::has(const std::string& key) const { return impl_->table.contains(key); }

bool Config::has_tables(const std::string& key) const
{
    const toml::node* n = impl_->table.get(key);
    return n && n->is_array_of_tables();
}

void Config::fail(const std::string& key, const std::string& why) const
{
    throw ConfigError(impl_->file, impl_->prefix + key, why);
}

std::string Config::get_string(const std::string& key, const std::string& def)
{
    impl_->known.insert(key);
    std::string v = def;
    if (const toml::node* n = impl_->table.get(key)) {
        if (!n->is_string()) fail(key, "must be a string, not " + type_name(*n));
        v = n->as_string()->get();
    }
    impl_->effective_here->insert_or_assign(key, v);
    return v;
}

std::string Config::get_enum(const std::string& key, const std::string& def, std::initializer_list<const char*> allowed)
{
    const std::string v = get_string(key, def);
    std::string list;
    for (const char* a : allowed) {
        if (v == a) return v;
        list += (list.empty() ? "" : ", ") + std::string("\"") + a + "\"";
    }
    fail(key, "\"" + v + "\" is not one of " + list);
}

bool Config::get_bool(const std::string& key, bool def)
{
    impl_->known.insert(key);
    bool v = def;
    if (const toml::node* n = impl_->table.get(key)) {
        if (!n->is_boolean()) fail(key, "must be true or false, not " + type_name(*n));
        v = n->as_boolean()->get();
    }
    impl_->effective_here->insert_or_assign(key, v);
    return v;
}

int64_t Config::get_int(const std::string& key, int64_t def, int64_t min, int64_t max)
{
    impl_->known.insert(key);
    int64_t v = def;
    if (const toml::node* n = impl_->table.get(key)) {
        if (!n->is_integer()) fail(key, "must be an integer, not " + type_name(*n));
        v = n->as_integer()->get();
        if (v < min || v > max)
            fail(key, std::to_string(v) + " is out of range [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    impl_->effective_here->insert_or_assign(key, v);
    return v;
}

int64_t Config::get_int(const std::string& key, int64_t def, std::initializer_list<int64_t> allowed)
{
    const int64_t v = get_int(key, def, INT64_MIN, INT64_MAX);
    std::string list;
    for (const int64_t a : allowed) {
        if (v == a) return v;
        list += (list.empty() ? "" : ", ") + std::to_string(a);
    }
    fail(key, std::to_string(v) + " is not one of " + list);
}

double Config::get_double(const std::string& key, double def, double min, double max)
{
    impl_->known.insert(key);
    double v = def;
    if (const toml::node* n = impl_->table.get(key)) {
        if (n->is_integer())
            v = static_cast<double>(n->as_integer()->get());
        else if (n->is_floating_point())
            v = n->as_floating_point()->get();
        else
            fail(key, "must be a number, not " + type_name(*n));
        if (!std::isfinite(v)) fail(key, "must be a finite number");
        if (v < min || v > max)
            fail(key, fmt_double(v) + " is out of range [" + fmt_double(min) + ", " + fmt_double(max) + "]");
    }
    impl_->effective_here->insert_or_assign(key, v);
    return v;
}

std::vector<double> Config::get_doubles(const std::string& key, const std::vector<double>& def, std::size_t n,
                                        double min, double max)
{
    impl_->known.insert(key);
    std::vector<double> v = def;
    if (const toml::node* node = impl_->table.get(key)) {
        const toml::array* a = node->as_array();
        if (!a) fail(key, "must be an array of numbers, not " + type_name(*node));
        if (n != 0 && a->size() != n) fail(key, "must have " + std::to_string(n) + " elements, not " + std::to_string(a->size()));
        v.clear();
        for (std::size_t k = 0; k < a->size(); ++k) {
            const toml::node& e = *a->get(k);
            double d = 0;
            if (e.is_integer())
                d = static_cast<double>(e.as_integer()->get());
            else if (e.is_floating_point())
                d = e.as_floating_point()->get();
            else
                fail(key, "element " + std::to_string(k) + " must be a number, not " + type_name(e));
            if (!std::isfinite(d) || d < min || d > max)
                fail(key, "element " + std::to_string(k) + " (" + fmt_double(d) + ") is out of range [" + fmt_double(min) +
                              ", " + fmt_double(max) + "]");
            v.push_back(d);
        }
    }
    toml::array out;
    for (const double d : v) out.push_back(d);
    impl_->effective_here->insert_or_assign(key, out);
    return v;
}

std::vector<std::string> Config::get_strings(const std::string& key, const std::vector<std::string>& def)
{
    impl_->known.insert(key);
    std::vector<std::string> v = def;
    if (const toml::node* node = impl_->table.get(key)) {
        const toml::array* a = node->as_array();
        if (!a) fail(key, "must be an array of strings, not " + type_name(*node));
        v.clear();
        for (std::size_t k = 0; k < a->size(); ++k) {
            const toml::node& e = *a->get(k);
            if (!e.is_string()) fail(key, "element " + std::to_string(k) + " must be a string, not " + type_name(e));
            v.push_back(e.as_string()->get());
        }
    }
    toml::array out;
    for (const auto& s : v) out.push_back(s);
    impl_->effective_here->insert_or_assign(key, out);
    return v;
}

std::string Config::get_channel(const std::string& key, const std::string& def)
{
    std::string v = get_string(key, def);
    if (const std::string why = channel_name_problem(v); !why.empty()) fail(key, why);
    return v;
}

std::string Config::get_channel_regex(const std::string& key, const std::string& def)
{
    std::string v = get_string(key, def);
    if (const std::string why = channel_regex_problem(v); !why.empty()) fail(key, why);
    return v;
}

Config Config::section(const std::string& name)
{
    impl_->known.insert(name);
    auto impl = std::make_unique<Impl>();
    impl->file = impl_->file;
    impl->prefix = impl_->prefix + name + ".";
    if (const toml::node* n = impl_->table.get(name)) {
        if (!n->is_table()) fail(name, "must be a table ([" + name + "]), not " + type_name(*n));
        impl->table = *n->as_table();
    }
    impl->effective = impl_->effective;
    auto [it, inserted] = impl_->effective_here->insert_or_assign(name, toml::table{});
    impl->effective_here = it->second.as_table();
    // Unknown keys inside the section are found by the parent's finish(): keep the table.
    Config child(std::move(impl));
    return child;
}

std::vector<Config> Config::tables(const std::string& name)
{
    impl_->known.insert(name);
    const toml::node* n = impl_->table.get(name);
    if (!n) return {};
    const toml::array* array = n->as_array();
    if (!array || !array->is_array_of_tables())
        fail(name, "must be an array of tables ([[" + name + "]]), not " + type_name(*n));
    auto [it, inserted] = impl_->effective_here->insert_or_assign(name, toml::array{});
    toml::array& effective = *it->second.as_array();
    for (std::size_t i = 0; i < array->size(); ++i) effective.push_back(toml::table{});
    std::vector<Config> out;
    for (std::size_t i = 0; i < array->size(); ++i) {
        auto impl = std::make_unique<Impl>();
        impl->file = impl_->file;
        impl->prefix = impl_->prefix + name + "[" + std::to_string(i) + "].";
        impl->table = *array->get(i)->as_table();
        impl->effective = impl_->effective;
        impl->effective_here = effective.get(i)->as_table();
        out.push_back(Config(std::move(impl)));
    }
    return out;
}

void Config::finish()
{
    for (auto&& [k, node] : impl_->table) {
        const std::string key(k.str());
        if (!impl_->known.count(key)) fail(key, "unknown key");
        // Sections were read through section(): check their keys against what was asked.
        if (node.is_table()) {
            const toml::table* eff = impl_->effective_here->get_as<toml::table>(key);
            for (auto&& [sk, sn] : *node.as_table()) {
                (void)sn;
                if (!eff || !eff->contains(sk.str())) fail(key + "." + std::string(sk.str()), "unknown key");
            }
        }
    }
}

std::string Config::effective_toml() const
{
    std::ostringstream s;
    s << *impl_->effective << "\n";
    return s.str();
}

}  // namespace ugv::runtime
