#pragma once
// The console's pages, styles and scripts, embedded at build time from
// src/app/console/ (CMakeLists.txt, dv_embed_text_files).

namespace dv {

struct EmbeddedConsoleAsset {
  const char* name;  // file name, e.g. "field.html"
  const char* text;
};

const EmbeddedConsoleAsset* embeddedConsoleAssets();
int embeddedConsoleAssetCount();

}  // namespace dv
