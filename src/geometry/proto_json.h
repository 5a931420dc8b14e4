#pragma once
// Protobuf's canonical JSON mapping, the on-disk form of league messages.
#include <google/protobuf/message.h>
#include <string>

namespace dv {

// One-line canonical JSON of a message (lowerCamelCase names, as protobuf
// prints them; parsers accept both those and the proto field names).
std::string toCanonicalJson(const google::protobuf::Message& m);

// Parses canonical JSON into `out`. Throws InputError naming `source` and,
// where protobuf reports it, the place and what is wrong; also when required
// fields are missing.
void parseCanonicalJson(const std::string& json, google::protobuf::Message& out,
                        const std::string& source);

}  // namespace dv
