#pragma once
// The shipped scene presets, embedded at build time from config/scenes/*.yaml
// (src/synth/scenes.cmake).

namespace dv {

struct EmbeddedScene {
  const char* name;  // file name, e.g. "side_view.yaml"
  const char* text;  // its YAML
};

const EmbeddedScene* embeddedScenes();
int embeddedSceneCount();

}  // namespace dv
