#include "geometry/calibration/view_hint.h"

#include <cmath>

#include "core/error.h"

namespace dv {

const char* regionHintNames() { return "x<0, x>0, x<0,y<0, x<0,y>0, x>0,y<0, x>0,y>0, center"; }

std::string ViewHint::describe() const {
  switch (kind) {
    case Kind::Region: return "--region " + text;
    case Kind::Near: return "--near " + text;
    case Kind::None: break;
  }
  return "";
}

ViewHint parseRegionHint(const std::string& text, const FieldModel& field, const std::string& source) {
  const double l = field.field_length / 2.0, w = field.field_width / 2.0;
  struct Named {
    const char* name;
    FieldRect rect;
  };
  const Named regions[] = {
      {"x<0", {-l, 0, -w, w}},     {"x>0", {0, l, -w, w}},      {"x<0,y<0", {-l, 0, -w, 0}},
      {"x<0,y>0", {-l, 0, 0, w}},  {"x>0,y<0", {0, l, -w, 0}},  {"x>0,y>0", {0, l, 0, w}},
      {"center", {-l / 2, l / 2, -w / 2, w / 2}}};
  for (const auto& r : regions)
    if (text == r.name) {
      ViewHint h;
      h.kind = ViewHint::Kind::Region;
      h.text = text;
      h.region = r.rect;
      return h;
    }
  throw InputError(source, "--region '" + text + "': expected one of " + regionHintNames());
}

ViewHint parseNearHint(const std::string& text, const FieldModel& field, const std::string& source) {
  const auto comma = text.find(',');
  double v[2];
  bool ok = comma != std::string::npos && text.find(',', comma + 1) == std::string::npos;
  for (int i = 0; i < 2 && ok; ++i) {
    const std::string item = i == 0 ? text.substr(0, comma) : text.substr(comma + 1);
    try {
      size_t used = 0;
      v[i] = std::stod(item, &used);
      ok = used == item.size() && std::isfinite(v[i]);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok) throw InputError(source, "--near '" + text + "': expected X,Y in mm (where the camera looks)");
  ViewHint h;
  h.kind = ViewHint::Kind::Near;
  h.text = text;
  h.near = {v[0], v[1]};
  if (!field.withBoundary().contains(h.near))
    throw InputError(source, "--near '" + text + "': the point is off the field and its boundary");
  return h;
}

}  // namespace dv
