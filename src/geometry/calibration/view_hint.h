#pragma once
// Where the operator says a camera looks, to settle the field's half-turn
// symmetry and to aim the automatic search: a named part of the field
// (--region) or a point (--near). Without one, the camera-id layout of
// SSL-Vision decides.
#include <string>

#include "core/units.h"
#include "geometry/field_model.h"

namespace dv {

struct ViewHint {
  enum class Kind { None, Region, Near };
  Kind kind = Kind::None;
  std::string text;      // as given, for messages: "x>0", "2000,-1500"
  FieldRect region;      // Kind::Region
  FieldMm near{0, 0};    // Kind::Near
  // "--region x>0" / "--near 2000,-1500" / "" for None.
  std::string describe() const;
};

// `text`: x<0, x>0, x<0,y<0, x<0,y>0, x>0,y<0, x>0,y>0 or center (the middle
// half of the field in both directions). Throws InputError(source, ...).
ViewHint parseRegionHint(const std::string& text, const FieldModel& field, const std::string& source);
// `text`: X,Y in mm, on the field or its boundary. Throws InputError(source, ...).
ViewHint parseNearHint(const std::string& text, const FieldModel& field, const std::string& source);

// The names parseRegionHint accepts, for help texts.
const char* regionHintNames();

}  // namespace dv
