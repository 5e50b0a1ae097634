// The JSON of an already decoded ugv message (a header of its own: ugv/reflect.hpp is
// included nearly everywhere, this only where a message is printed after its decode).
#pragma once

#include <string>

namespace ugv::reflect {

// The same JSON as to_json() of the message's bytes, for a message the caller decoded already
// (ugv-mcap decodes a map once for its raw and its grid topic). Defined for every ugv type;
// json is replaced, its capacity kept.
template <typename Msg>
void message_json(const Msg& msg, std::string& json);

}  // namespace ugv::reflect
