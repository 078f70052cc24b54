// A small streaming JSON writer for metrics files (stable key order, as written).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace coopmap {

class JsonWriter {
 public:
  JsonWriter& beginObject(std::string_view key = {});
  JsonWriter& endObject();
  JsonWriter& beginArray(std::string_view key = {});
  JsonWriter& endArray();
  JsonWriter& value(std::string_view key, double v);
  JsonWriter& value(std::string_view key, long long v);
  JsonWriter& value(std::string_view key, unsigned long long v);
  JsonWriter& value(std::string_view key, int v) { return value(key, static_cast<long long>(v)); }
  JsonWriter& value(std::string_view key, bool v);
  JsonWriter& value(std::string_view key, std::string_view v);
  JsonWriter& value(std::string_view key, const char* v) { return value(key, std::string_view(v)); }
  // The document so far (complete once every object/array is closed), ending in a newline.
  std::string str() const {
    std::string s = out_;
    s += '\n';
    return s;
  }

  static std::string quote(std::string_view s);

 private:
  void prefix(std::string_view key);
  void newline();
  std::string out_;
  std::vector<bool> first_;  // per open container: nothing written yet
};

}  // namespace coopmap
