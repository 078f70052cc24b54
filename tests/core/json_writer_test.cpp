#include "core/io/json_writer.h"

#include <gtest/gtest.h>

namespace coopmap {
namespace {

TEST(JsonWriterTest, WritesNestedObjectsWithStableKeyOrder) {
  JsonWriter j;
  j.beginObject();
  j.value("b", 1).value("a", 0.5).value("ok", true).value("name", "jo\"se\n");
  j.beginObject("map").value("coverage", 0.75).endObject();
  j.beginArray("empty").endArray();
  j.beginObject("none").endObject();
  j.endObject();
  EXPECT_EQ(j.str(),
            "{\n  \"b\": 1,\n  \"a\": 0.5,\n  \"ok\": true,\n  \"name\": \"jo\\\"se\\n\",\n"
            "  \"map\": {\n    \"coverage\": 0.75\n  },\n  \"empty\": [],\n  \"none\": {}\n}\n");
}

TEST(JsonWriterTest, NonFiniteNumbersBecomeNull) {
  JsonWriter j;
  j.beginObject().value("x", 1.0 / 0.0).endObject();
  EXPECT_EQ(j.str(), "{\n  \"x\": null\n}\n");
}

}  // namespace
}  // namespace coopmap
