// Stand-in for the conformance suite where the league's reference schemas
// (../shared/reference/proto, next to the repository) were not found at
// configure time, e.g. in a user's clone. It reports a visible skip rather
// than silently passing.
#include <gtest/gtest.h>

TEST(SchemaConformance, ReferenceSchemasPresent) {
  GTEST_SKIP() << "skipped: ../shared/reference/proto not found "
                  "(re-run cmake with the league's .proto files there to check wire conformance)";
}
