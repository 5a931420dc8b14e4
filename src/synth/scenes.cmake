# The scene presets (config/scenes/*.yaml) embedded into dv_synth, so that a
# binary moved away from its source tree still knows them.
file(GLOB DV_SCENE_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/config/scenes/*.yaml)
list(SORT DV_SCENE_FILES)
string(REPLACE ";" "|" DV_SCENE_FILES_ARG "${DV_SCENE_FILES}")
set(DV_EMBEDDED_SCENES_CPP ${PROJECT_BINARY_DIR}/synth/embedded_scenes.cpp)
add_custom_command(OUTPUT ${DV_EMBEDDED_SCENES_CPP}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/synth
  COMMAND ${CMAKE_COMMAND} -DOUT=${DV_EMBEDDED_SCENES_CPP} -DFILES=${DV_SCENE_FILES_ARG}
          -DHEADER=synth/embedded_scenes.h -DNAME=Scene
          -P ${PROJECT_SOURCE_DIR}/cmake/embed_text_files.cmake
  DEPENDS ${DV_SCENE_FILES} ${PROJECT_SOURCE_DIR}/cmake/embed_text_files.cmake
  COMMENT "Embedding scene presets" VERBATIM)
target_sources(dv_synth PRIVATE ${DV_EMBEDDED_SCENES_CPP})
