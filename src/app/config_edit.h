#pragma once
// Edits of a YAML config by key, as the console's settings page makes them:
// the value of an existing key is replaced where it is written, so the
// file's comments and layout stay (the operator's site file is theirs); a
// key the text does not have yet is added by rewriting the document, which
// loses its comments (`layout_kept` says so). The result is only text: it is
// validated as a whole by the caller (parseSiteConfig).
#include <string>
#include <utility>
#include <vector>

namespace dv::app {

struct ConfigEdit {
  std::string key;    // dotted path of map keys, e.g. "robot_heights.default"
  std::string value;  // a YAML flow scalar: 130, true, null, "Team name"
};

struct ConfigEditResult {
  std::string text;
  bool layout_kept = true;
};

// Throws InputError(source, ...) when the text is not YAML or a key's path
// runs through something that is not a map.
ConfigEditResult editConfigText(const std::string& text, const std::vector<ConfigEdit>& edits,
                                const std::string& source);

}  // namespace dv::app
