#include "ugv/expect/json_value.hpp"

#include <cstdlib>

namespace ugv::expect {
namespace {

class Parser
{
public:
    explicit Parser(std::string_view s) : s_(s) {}

    bool value(JsonValue& v)
    {
        skip();
        if (p_ >= s_.size()) return false;
        const char c = s_[p_];
        if (c == '{') return object(v);
        if (c == '[') return array(v);
        if (c == '"') {
            v.kind = JsonValue::Kind::string;
            return string(v.string);
        }
        if (literal("null")) {
            v.kind = JsonValue::Kind::null;
            return true;
        }
        if (literal("true") || literal("false")) {
            v.kind = JsonValue::Kind::boolean;
            v.boolean = s_[p_ - 1] == 'e' && s_[p_ - 2] == 'u';
            return true;
        }
        return number(v);
    }
    bool at_end()
    {
        skip();
        return p_ == s_.size();
    }

private:
    void skip()
    {
        while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\n' || s_[p_] == '\t' || s_[p_] == '\r')) ++p_;
    }
    bool literal(std::string_view w)
    {
        if (s_.substr(p_, w.size()) != w) return false;
        p_ += w.size();
        return true;
    }
    bool number(JsonValue& v)
    {
        const std::string tmp(s_.substr(p_, 40));
        char* end = nullptr;
        v.number = std::strtod(tmp.c_str(), &end);
        if (end == tmp.c_str()) return false;
        p_ += static_cast<std::size_t>(end - tmp.c_str());
        v.kind = JsonValue::Kind::number;
        return true;
    }
    bool string(std::string& out)
    {
        ++p_;  // opening quote
        while (p_ < s_.size() && s_[p_] != '"') {
            char c = s_[p_++];
            if (c == '\\' && p_ < s_.size()) {
                const char e = s_[p_++];
                switch (e) {
                case 'n': c = '\n'; break;
                case 't': c = '\t'; break;
                case 'r': c = '\r'; break;
                case 'u': {
                    if (p_ + 4 > s_.size()) return false;
                    c = static_cast<char>(std::strtol(std::string(s_.substr(p_, 4)).c_str(), nullptr, 16));
                    p_ += 4;
                    break;
                }
                default: c = e;
                }
            }
            out += c;
        }
        if (p_ >= s_.size()) return false;
        ++p_;
        return true;
    }
    bool array(JsonValue& v)
    {
        v.kind = JsonValue::Kind::array;
        ++p_;
        skip();
        if (p_ < s_.size() && s_[p_] == ']') return ++p_, true;
        while (true) {
            v.array.emplace_back();
            if (!value(v.array.back())) return false;
            skip();
            if (p_ < s_.size() && s_[p_] == ',') {
                ++p_;
                continue;
            }
            if (p_ < s_.size() && s_[p_] == ']') return ++p_, true;
            return false;
        }
    }
    bool object(JsonValue& v)
    {
        v.kind = JsonValue::Kind::object;
        ++p_;
        skip();
        if (p_ < s_.size() && s_[p_] == '}') return ++p_, true;
        while (true) {
            skip();
            if (p_ >= s_.size() || s_[p_] != '"') return false;
            std::string key;
            if (!string(key)) return false;
            skip();
            if (p_ >= s_.size() || s_[p_] != ':') return false;
            ++p_;
            if (!value(v.object[key])) return false;
            skip();
            if (p_ < s_.size() && s_[p_] == ',') {
                ++p_;
                continue;
            }
            if (p_ < s_.size() && s_[p_] == '}') return ++p_, true;
            return false;
        }
    }

    std::string_view s_;
    std::size_t p_ = 0;
};

}  // namespace

std::optional<JsonValue> parse_json(std::string_view text)
{
    Parser p(text);
    JsonValue v;
    if (!p.value(v) || !p.at_end()) return std::nullopt;
    return v;
}

}  // namespace ugv::expect
