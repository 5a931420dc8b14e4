#include "app/config_edit.h"

#include <sstream>
#include <yaml-cpp/yaml.h>

#include "core/error.h"

namespace dv::app {

namespace {

std::vector<std::string> splitKey(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  std::string p;
  while (std::getline(ss, p, '.')) parts.push_back(p);
  return parts;
}

YAML::Node load(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(source, "YAML syntax error: " + e.msg);
  }
}

// Where the scalar value of `key` is written in `text`: [begin, end), or
// false when the key is absent or its value is not a one-line scalar.
bool findScalar(const std::string& text, const std::string& key, size_t& begin, size_t& end,
                const std::string& source) {
  YAML::Node node = load(text, source);
  for (const std::string& part : splitKey(key)) {
    if (!node.IsMap()) {
      if (node.IsDefined() && !node.IsNull())
        throw InputError(source, "key '" + key + "': '" + part + "' is not inside a map");
      return false;
    }
    const YAML::Node next = static_cast<const YAML::Node&>(node)[part];  // const: no key created
    if (!next.IsDefined()) return false;
    node.reset(next);
  }
  if (!node.IsScalar() && !node.IsNull()) return false;  // `null` and `~` are written values too
  const int pos = node.Mark().pos;
  if (pos < 0 || size_t(pos) >= text.size()) return false;
  begin = size_t(pos);
  const char q = text[begin];
  if (q == '"' || q == '\'') {
    // The closing quote (a doubled '' or an escaped \" does not close).
    for (size_t i = begin + 1; i < text.size() && text[i] != '\n'; ++i) {
      if (q == '"' && text[i] == '\\') {
        ++i;
        continue;
      }
      if (text[i] == q) {
        if (q == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
          ++i;
          continue;
        }
        end = i + 1;
        return true;
      }
    }
    return false;
  }
  end = begin;
  while (end < text.size() && text[end] != '\n' && text[end] != ',' && text[end] != '}' && text[end] != ']' &&
         !(text[end] == '#' && end > begin && (text[end - 1] == ' ' || text[end - 1] == '\t')))
    ++end;
  while (end > begin && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
  // A sanity check: the span read back is the value yaml-cpp read.
  const YAML::Node back = load(text.substr(begin, end - begin), source);
  return end > begin && back.Type() == node.Type() && (!node.IsScalar() || back.Scalar() == node.Scalar());
}

}  // namespace

ConfigEditResult editConfigText(const std::string& text, const std::vector<ConfigEdit>& edits,
                                const std::string& source) {
  ConfigEditResult r;
  r.text = text;
  for (const ConfigEdit& e : edits) {
    if (e.key.empty()) throw InputError(source, "an edit names no key");
    size_t begin = 0, end = 0;
    if (findScalar(r.text, e.key, begin, end, source)) {
      r.text.replace(begin, end - begin, e.value);
      continue;
    }
    // Absent (or not a one-line scalar): set it in the tree and rewrite.
    YAML::Node root = load(r.text, source);
    if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    std::vector<YAML::Node> chain{root};
    const std::vector<std::string> parts = splitKey(e.key);
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
      YAML::Node child = chain.back()[parts[i]];
      if (!child.IsDefined() || child.IsNull()) {
        chain.back()[parts[i]] = YAML::Node(YAML::NodeType::Map);
        child.reset(chain.back()[parts[i]]);
      } else if (!child.IsMap()) {
        throw InputError(source, "key '" + e.key + "': '" + parts[i] + "' is not a map");
      }
      chain.push_back(child);
    }
    chain.back()[parts.back()] = load(e.value, source);
    YAML::Emitter out;
    out << root;
    r.text = std::string(out.c_str()) + "\n";
    r.layout_kept = false;
  }
  return r;
}

}  // namespace dv::app
