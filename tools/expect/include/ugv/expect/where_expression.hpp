// The --where condition of ugv-expect, evaluated on a message's fields:
//   TERM [&& TERM ...]      TERM = PATH OP VALUE
//   PATH   = name(.name | [index])* with an optional trailing .size()   e.g. ranges.size(),
//            pose.position[0], counter_values[2]
//   OP     = == != < <= > >=
//   VALUE  = a number, true/false, or a "string"
// A NaN field (null in JSON) compares false with everything except `!= x`.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "ugv/expect/json_value.hpp"

namespace ugv::expect {

class WhereExpression
{
public:
    // Throws std::invalid_argument with a one-line reason for a malformed expression.
    explicit WhereExpression(const std::string& text);
    // True when every term holds for the message's fields (the "fields" object).
    bool matches(const JsonValue& fields) const;
    const std::string& text() const { return text_; }

private:
    struct Step
    {
        std::string name;  // field name, or empty for an index step
        long index = -1;
    };
    struct Term
    {
        std::vector<Step> path;
        bool size = false;
        std::string op;
        JsonValue value;
    };
    bool holds(const Term& t, const JsonValue& fields) const;

    std::string text_;
    std::vector<Term> terms_;
};

}  // namespace ugv::expect
