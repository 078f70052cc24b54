// Reading YAML configuration with errors that name the file, the line and the field, and
// say what was expected: "worlds/lab.yaml:12:5: walls[3].thickness: expected a positive
// number, got '-0.1'".
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>

namespace coopmap {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A node of a YAML document with the file and field path it came from.
class YamlField {
 public:
  // Parses a file; throws ConfigError with file and line on syntax errors or a missing file.
  static YamlField loadFile(const std::string& path);
  // Parses text (the `file` name is used in messages only).
  static YamlField loadString(const std::string& text, const std::string& file);

  YamlField(YAML::Node node, std::string file, std::string path, int line, int column);

  bool has(const std::string& key) const;
  // A required mapping key; throws naming the key and the mapping's line when absent.
  YamlField operator[](const std::string& key) const;
  // An optional mapping key.
  std::optional<YamlField> get(const std::string& key) const;
  // Elements of a sequence (throws unless this is a sequence).
  std::vector<YamlField> elements() const;
  // Keys of a mapping, in file order (throws unless this is a mapping).
  std::vector<std::string> keys() const;
  // Throws if the mapping has keys outside `allowed` (catches typos).
  void allowOnly(const std::vector<std::string>& allowed) const;

  double asDouble() const;
  // A number in [lo, hi]; `what` describes the range for the message.
  double asDouble(double lo, double hi, const std::string& what) const;
  int asInt(int lo, int hi) const;
  bool asBool() const;
  std::string asString() const;
  std::string asEnum(const std::vector<std::string>& choices) const;
  Eigen::Vector2d asVector2() const;
  Eigen::Vector3d asVector3() const;

  bool isSequence() const { return node_.IsSequence(); }
  bool isMap() const { return node_.IsMap(); }
  bool isScalar() const { return node_.IsScalar(); }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  int line() const { return line_; }

  // Throws ConfigError "file:line:col: path: expected <expected>, got '<value>'".
  [[noreturn]] void fail(const std::string& expected) const;
  // Same location prefix with a free message.
  [[noreturn]] void failMessage(const std::string& message) const;
  // The location prefix "file:line:col: path".
  std::string where() const;

 private:
  std::string got() const;
  YAML::Node node_;
  std::string file_;
  std::string path_;
  int line_ = 0;    // 1-based; 0 unknown
  int column_ = 0;  // 1-based
};

// Optional value helpers: the field's value when present, else `fallback`.
double optionalDouble(const YamlField& parent, const std::string& key, double fallback, double lo,
                      double hi, const std::string& what);

}  // namespace coopmap
