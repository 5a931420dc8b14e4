#include "camera/genicam_features.h"

#include <arv.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "camera/aravis_error.h"
#include "core/error.h"

namespace dv {

namespace {

bool parseInt(const std::string& text, gint64& v) {
  const char* b = text.data();
  const char* e = b + text.size();
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) b += 2, base = 16;
  long long x = 0;
  auto [p, ec] = std::from_chars(b, e, x, base);
  if (ec != std::errc() || p != e) return false;
  v = x;
  return true;
}

bool parseFloat(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(v);
}

bool parseBool(const std::string& text, gboolean& v) {
  std::string t;
  for (char c : text) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "1" || t == "on" || t == "yes") return v = TRUE, true;
  if (t == "false" || t == "0" || t == "off" || t == "no") return v = FALSE, true;
  return false;
}

std::string numberText(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// Older cameras (and Aravis's fake one) name the SFNC features with a
// suffix: ExposureTimeAbs, GainRaw. Suggest the other spelling if it exists.
std::string suggestion(ArvDevice* device, const std::string& name) {
  std::vector<std::string> candidates = {name + "Abs", name + "Raw"};
  for (const char* suffix : {"Abs", "Raw"}) {
    const std::string s = suffix;
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0)
      candidates.push_back(name.substr(0, name.size() - s.size()));
  }
  for (const auto& c : candidates)
    if (arv_device_get_feature(device, c.c_str())) return " (did you mean " + c + "?)";
  return " (GenICam names are case-sensitive, e.g. ExposureTime, Gain, PixelFormat)";
}

std::string unitOf(ArvGcNode* node) {
  const char* u = nullptr;
  if (ARV_IS_GC_FLOAT(node)) u = arv_gc_float_get_unit(ARV_GC_FLOAT(node));
  else if (ARV_IS_GC_INTEGER(node) && !ARV_IS_GC_ENUMERATION(node)) u = arv_gc_integer_get_unit(ARV_GC_INTEGER(node));
  return u && *u ? std::string(" (") + u + ")" : std::string();
}

std::string joinAvailable(ArvGcEnumeration* e) {
  guint n = 0;
  GError* error = nullptr;
  const char** values = arv_gc_enumeration_dup_available_string_values(e, &n, &error);
  g_clear_error(&error);
  std::string out;
  for (guint i = 0; values && i < n; ++i) out += (i ? ", " : "") + std::string(values[i]);
  g_free(values);
  return out;
}

}  // namespace

std::string genicamFeatureText(ArvDevice* device, const char* name) {
  ArvGcNode* node = arv_device_get_feature(device, name);
  if (!node || !ARV_IS_GC_FEATURE_NODE(node)) return {};
  GError* error = nullptr;
  const char* v = arv_gc_feature_node_get_value_as_string(ARV_GC_FEATURE_NODE(node), &error);
  g_clear_error(&error);
  return v ? v : "";
}

std::string setGenicamFeature(ArvDevice* device, const CameraSetting& s, const std::string& source,
                              const std::string& camera) {
  const std::string& name = s.name;
  const std::string& value = s.value;
  auto fail = [&](const std::string& what) {
    throw InputError(source, "camera setting " + name + "=" + value + " on " + camera + ": " + what);
  };
  ArvGcNode* node = arv_device_get_feature(device, name.c_str());
  GError* error = nullptr;
  if (!node || !ARV_IS_GC_FEATURE_NODE(node) ||
      !arv_gc_feature_node_is_implemented(ARV_GC_FEATURE_NODE(node), &error)) {
    g_clear_error(&error);
    fail("the camera has no feature '" + name + "'" + suggestion(device, name));
  }
  ArvGcFeatureNode* feature = ARV_GC_FEATURE_NODE(node);
  if (!arv_gc_feature_node_is_available(feature, &error)) {
    g_clear_error(&error);
    fail("feature '" + name + "' is not available now (another setting disables it)");
  }
  if (!ARV_IS_GC_COMMAND(node)) {
    if (arv_gc_feature_node_get_actual_access_mode(feature) == ARV_GC_ACCESS_MODE_RO)
      fail("feature '" + name + "' is read-only");
    if (arv_gc_feature_node_is_locked(feature, &error)) {
      g_clear_error(&error);
      fail("feature '" + name + "' is locked (stop acquisition or unlock TLParamsLocked first)");
    }
    g_clear_error(&error);
  }

  double asked_number = NAN;
  if (ARV_IS_GC_ENUMERATION(node)) {
    auto* e = ARV_GC_ENUMERATION(node);
    if (!arv_gc_enumeration_set_string_value(e, value.c_str(), &error) || error) {
      const std::string why = takeErrorMessage(error);
      fail("refused (" + why + "); the camera offers: " + joinAvailable(e));
    }
  } else if (ARV_IS_GC_BOOLEAN(node)) {
    gboolean b = FALSE;
    if (!parseBool(value, b)) fail("'" + value + "' is not a boolean (true/false, 1/0, on/off)");
    arv_gc_boolean_set_value(ARV_GC_BOOLEAN(node), b, &error);
  } else if (ARV_IS_GC_COMMAND(node)) {
    arv_gc_command_execute(ARV_GC_COMMAND(node), &error);
  } else if (ARV_IS_GC_INTEGER(node)) {
    auto* i = ARV_GC_INTEGER(node);
    gint64 v = 0;
    if (!parseInt(value, v)) fail("'" + value + "' is not an integer");
    const gint64 lo = arv_gc_integer_get_min(i, nullptr), hi = arv_gc_integer_get_max(i, nullptr);
    if (lo < hi && (v < lo || v > hi))
      fail("out of range " + std::to_string(lo) + " .. " + std::to_string(hi));
    arv_gc_integer_set_value(i, v, &error);
    asked_number = static_cast<double>(v);
  } else if (ARV_IS_GC_FLOAT(node)) {
    auto* f = ARV_GC_FLOAT(node);
    double v = 0;
    if (!parseFloat(value, v)) fail("'" + value + "' is not a number");
    const double lo = arv_gc_float_get_min(f, nullptr), hi = arv_gc_float_get_max(f, nullptr);
    if (lo < hi && (v < lo || v > hi)) fail("out of range " + numberText(lo) + " .. " + numberText(hi));
    arv_gc_float_set_value(f, v, &error);
    asked_number = v;
  } else if (ARV_IS_GC_STRING(node)) {
    arv_gc_string_set_value(ARV_GC_STRING(node), value.c_str(), &error);
  } else {
    fail("feature '" + name + "' is of a kind that cannot be set from text");
  }
  if (error) fail("refused by the camera: " + takeErrorMessage(error));
  if (ARV_IS_GC_COMMAND(node)) return name + " executed";

  const char* back = arv_gc_feature_node_get_value_as_string(feature, &error);
  if (error || !back) fail("set, but it cannot be read back: " + takeErrorMessage(error));
  std::string line = name + " = " + back + unitOf(node);
  double got = 0;
  if (!std::isnan(asked_number) && parseFloat(back, got) &&
      std::fabs(got - asked_number) > 1e-6 * std::max(1.0, std::fabs(asked_number)))
    line += " (asked " + value + ")";
  return line;
}

}  // namespace dv
