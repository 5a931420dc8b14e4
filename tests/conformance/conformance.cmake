# Wire conformance of dotvision's own schemas (proto/dotvision, package
# dv.ssl) against the league's reference schemas in ../shared/reference/proto.
# The reference files are compiled into this test executable only, never into
# the product. Where a clone has no ../shared, a stand-in test reports the
# skip through GTest so ctest lists it.
set(DV_REFERENCE_PROTO_DIR "${PROJECT_SOURCE_DIR}/../shared/reference/proto")
# The vision schemas and the referee message with its import closure. The
# tracked vision files are left out: they and the game-controller files
# define the same global messages (Vector2, ...), and we have no copy of them.
set(DV_REFERENCE_PROTO_NAMES
  messages_robocup_ssl_detection
  messages_robocup_ssl_geometry
  messages_robocup_ssl_wrapper
  messages_robocup_ssl_geometry_legacy
  messages_robocup_ssl_wrapper_legacy
  state/ssl_gc_referee_message
  state/ssl_gc_game_event
  state/ssl_gc_common
  geom/ssl_gc_geometry)

set(DV_REFERENCE_PROTO_FOUND TRUE)
foreach(name ${DV_REFERENCE_PROTO_NAMES})
  if(NOT EXISTS "${DV_REFERENCE_PROTO_DIR}/${name}.proto")
    set(DV_REFERENCE_PROTO_FOUND FALSE)
  endif()
endforeach()

if(DV_REFERENCE_PROTO_FOUND)
  get_filename_component(DV_REFERENCE_PROTO_DIR "${DV_REFERENCE_PROTO_DIR}" REALPATH)
  set(DV_REFERENCE_PROTO_OUT "${CMAKE_CURRENT_BINARY_DIR}/reference_proto")
  file(MAKE_DIRECTORY "${DV_REFERENCE_PROTO_OUT}")
  set(DV_REFERENCE_PROTO_SRCS)
  foreach(name ${DV_REFERENCE_PROTO_NAMES})
    set(src "${DV_REFERENCE_PROTO_DIR}/${name}.proto")
    set(cc "${DV_REFERENCE_PROTO_OUT}/${name}.pb.cc")
    add_custom_command(OUTPUT "${cc}" "${DV_REFERENCE_PROTO_OUT}/${name}.pb.h"
      COMMAND protobuf::protoc --cpp_out=${DV_REFERENCE_PROTO_OUT} -I ${DV_REFERENCE_PROTO_DIR} ${src}
      DEPENDS "${src}" protobuf::protoc VERBATIM)
    list(APPEND DV_REFERENCE_PROTO_SRCS "${cc}")
  endforeach()
  set_source_files_properties(${DV_REFERENCE_PROTO_SRCS} PROPERTIES COMPILE_OPTIONS "-w")
  add_executable(dotvision_conformance_tests
    ${CMAKE_CURRENT_LIST_DIR}/wire_conformance_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/referee_conformance_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/proto_reflection.cpp
    ${DV_REFERENCE_PROTO_SRCS})
  target_include_directories(dotvision_conformance_tests PRIVATE
    "${DV_REFERENCE_PROTO_OUT}" "${CMAKE_CURRENT_LIST_DIR}")
else()
  message(STATUS "conformance: ../shared/reference/proto not found; the conformance test will report a skip")
  add_executable(dotvision_conformance_tests
    ${CMAKE_CURRENT_LIST_DIR}/reference_missing_test.cpp)
endif()

target_link_libraries(dotvision_conformance_tests PRIVATE dv_proto GTest::gtest GTest::gtest_main)
include(GoogleTest)
gtest_discover_tests(dotvision_conformance_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
