#include "geometry/proto_json.h"

#include <google/protobuf/util/json_util.h>

#include "core/error.h"

namespace dv {

std::string toCanonicalJson(const google::protobuf::Message& m) {
  std::string out;
  google::protobuf::util::JsonPrintOptions opt;
  opt.add_whitespace = false;
  auto st = google::protobuf::util::MessageToJsonString(m, &out, opt);
  if (!st.ok()) throw std::runtime_error("cannot print " + m.GetTypeName() + ": " + st.ToString());
  return out;
}

void parseCanonicalJson(const std::string& json, google::protobuf::Message& out,
                        const std::string& source) {
  google::protobuf::util::JsonParseOptions opt;
  opt.ignore_unknown_fields = false;
  out.Clear();
  auto st = google::protobuf::util::JsonStringToMessage(json, &out, opt);
  if (!st.ok()) {
    throw InputError(source, "not a valid " + out.GetTypeName() + " in canonical JSON: " +
                                 std::string(st.message()));
  }
  if (!out.IsInitialized()) {
    throw InputError(source, out.GetTypeName() + " lacks required fields: " +
                                 out.InitializationErrorString());
  }
}

}  // namespace dv
