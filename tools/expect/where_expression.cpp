#include "ugv/expect/where_expression.hpp"

#include <cctype>
#include <cmath>

namespace ugv::expect {
namespace {

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

template <typename T>
bool compare(const T& a, const std::string& op, const T& b)
{
    if (op == "==") return a == b;
    if (op == "!=") return a != b;
    if (op == "<") return a < b;
    if (op == "<=") return a <= b;
    if (op == ">") return a > b;
    return a >= b;
}

}  // namespace

WhereExpression::WhereExpression(const std::string& text) : text_(text)
{
    std::size_t start = 0;
    while (start <= text.size()) {
        const auto amp = text.find("&&", start);
        const std::string term_text = trim(text.substr(start, amp == std::string::npos ? std::string::npos : amp - start));
        start = amp == std::string::npos ? text.size() + 1 : amp + 2;
        if (term_text.empty()) throw std::invalid_argument("empty condition in '" + text + "'");
        Term t;
        std::size_t op_pos = std::string::npos;
        for (const char* op : {"==", "!=", "<=", ">=", "<", ">"}) {
            const auto p = term_text.find(op);
            if (p != std::string::npos && (op_pos == std::string::npos || p < op_pos)) {
                op_pos = p;
                t.op = op;
            }
        }
        if (op_pos == std::string::npos) throw std::invalid_argument("no comparison (== != < <= > >=) in '" + term_text + "'");
        std::string path = trim(term_text.substr(0, op_pos));
        const std::string value = trim(term_text.substr(op_pos + t.op.size()));
        if (path.size() > 7 && path.compare(path.size() - 7, 7, ".size()") == 0) {
            t.size = true;
            path.resize(path.size() - 7);
        }
        std::size_t p = 0;
        while (p < path.size()) {
            if (path[p] == '.') {
                ++p;
                continue;
            }
            if (path[p] == '[') {
                const auto close = path.find(']', p);
                if (close == std::string::npos) throw std::invalid_argument("unclosed [ in '" + path + "'");
                Step s;
                try {
                    s.index = std::stol(path.substr(p + 1, close - p - 1));
                } catch (const std::exception&) {
                    throw std::invalid_argument("bad index in '" + path + "'");
                }
                t.path.push_back(s);
                p = close + 1;
                continue;
            }
            std::size_t q = p;
            while (q < path.size() && (std::isalnum(static_cast<unsigned char>(path[q])) || path[q] == '_')) ++q;
            if (q == p) throw std::invalid_argument("bad field path '" + path + "'");
            t.path.push_back(Step{path.substr(p, q - p), -1});
            p = q;
        }
        if (t.path.empty()) throw std::invalid_argument("no field in '" + term_text + "'");
        auto v = parse_json(value);
        if (!v || (v->kind != JsonValue::Kind::number && v->kind != JsonValue::Kind::string && v->kind != JsonValue::Kind::boolean))
            throw std::invalid_argument("'" + value + "' is not a number, true/false or a \"string\"");
        t.value = *v;
        terms_.push_back(std::move(t));
    }
}

bool WhereExpression::holds(const Term& t, const JsonValue& fields) const
{
    const JsonValue* v = &fields;
    for (const Step& s : t.path) {
        if (!s.name.empty()) {
            if (v->kind != JsonValue::Kind::object) return false;
            const auto it = v->object.find(s.name);
            if (it == v->object.end()) return false;
            v = &it->second;
        } else {
            if (v->kind != JsonValue::Kind::array || s.index < 0 || static_cast<std::size_t>(s.index) >= v->array.size())
                return false;
            v = &v->array[static_cast<std::size_t>(s.index)];
        }
    }
    if (t.size) {
        if (v->kind == JsonValue::Kind::array) return compare(static_cast<double>(v->array.size()), t.op, t.value.number);
        if (v->kind == JsonValue::Kind::string) return compare(static_cast<double>(v->string.size()), t.op, t.value.number);
        return false;
    }
    if (v->kind == JsonValue::Kind::null) return t.op == "!=";  // NaN
    if (t.value.kind == JsonValue::Kind::number && v->kind == JsonValue::Kind::number)
        return compare(v->number, t.op, t.value.number);
    if (t.value.kind == JsonValue::Kind::number && v->kind == JsonValue::Kind::boolean)
        return compare(v->boolean ? 1.0 : 0.0, t.op, t.value.number);
    if (t.value.kind == JsonValue::Kind::boolean && v->kind == JsonValue::Kind::boolean)
        return compare(v->boolean, t.op, t.value.boolean);
    if (t.value.kind == JsonValue::Kind::string && v->kind == JsonValue::Kind::string)
        return compare(v->string, t.op, t.value.string);
    return false;
}

bool WhereExpression::matches(const JsonValue& fields) const
{
    for (const Term& t : terms_)
        if (!holds(t, fields)) return false;
    return true;
}

}  // namespace ugv::expect
