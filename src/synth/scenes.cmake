# The scene presets (config/scenes/*.yaml) embedded into dv_synth, so that a
# binary moved away from its source tree still knows them.
file(GLOB DV_SCENE_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/config/scenes/*.yaml)
dv_embed_text_files(dv_synth Scene synth/embedded_scenes.h
                    ${PROJECT_BINARY_DIR}/synth/embedded_scenes.cpp ${DV_SCENE_FILES})
