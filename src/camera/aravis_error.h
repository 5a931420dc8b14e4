#pragma once
// GError (Aravis / GLib) to text, freeing it.
#include <glib.h>

#include <string>

namespace dv {

inline std::string takeErrorMessage(GError*& error) {
  std::string m = error && error->message ? error->message : "unknown error";
  g_clear_error(&error);
  return m;
}

}  // namespace dv
