#include "core/io/yaml_reader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace coopmap {

namespace {
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

// A mapping that names a key twice: yaml-cpp keeps one of the two silently, and a setting
// written twice would be read as whichever it kept. Refused, naming the second.
void refuseDuplicateKeys(const YAML::Node& node, const std::string& file) {
  if (node.IsSequence()) {
    for (const YAML::Node& child : node) refuseDuplicateKeys(child, file);
    return;
  }
  if (!node.IsMap()) return;
  std::vector<std::string> seen;
  for (const auto& item : node) {
    const YAML::Node& key = item.first;
    if (key.IsScalar()) {
      if (std::find(seen.begin(), seen.end(), key.Scalar()) != seen.end())
        throw ConfigError(file + ":" + std::to_string(key.Mark().line + 1) + ":" +
                          std::to_string(key.Mark().column + 1) + ": key '" + key.Scalar() +
                          "' given twice in one mapping");
      seen.push_back(key.Scalar());
    }
    refuseDuplicateKeys(item.second, file);
  }
}

YamlField parse(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw ConfigError(file + ":1:1: expected a YAML mapping at the top level");
  refuseDuplicateKeys(root, file);
  return YamlField(root, file, "", 1, 1);
}
}  // namespace

YamlField YamlField::loadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

YamlField YamlField::loadString(const std::string& text, const std::string& file) {
  return parse(text, file);
}

YamlField::YamlField(YAML::Node node, std::string file, std::string path, int line, int column)
    : node_(std::move(node)),
      file_(std::move(file)),
      path_(std::move(path)),
      line_(line),
      column_(column) {
  if (node_.IsDefined() && node_.Mark().line >= 0) {
    line_ = node_.Mark().line + 1;
    column_ = node_.Mark().column + 1;
  }
}

std::string YamlField::where() const {
  std::string w = file_;
  if (line_ > 0) w += ":" + std::to_string(line_) + ":" + std::to_string(column_);
  return w + ": " + (path_.empty() ? std::string("(top level)") : path_);
}

std::string YamlField::got() const {
  if (!node_.IsDefined() || node_.IsNull()) return "nothing";
  if (node_.IsScalar()) return "'" + node_.Scalar() + "'";
  if (node_.IsSequence()) return "a list";
  return "a mapping";
}

void YamlField::fail(const std::string& expected) const {
  throw ConfigError(where() + ": expected " + expected + ", got " + got());
}

void YamlField::failMessage(const std::string& message) const {
  throw ConfigError(where() + ": " + message);
}

bool YamlField::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined();
}

YamlField YamlField::operator[](const std::string& key) const {
  if (!node_.IsMap()) fail("a mapping with key '" + key + "'");
  const YAML::Node child = node_[key];
  const std::string child_path = path_.empty() ? key : path_ + "." + key;
  if (!child.IsDefined())
    throw ConfigError(where() + ": missing required field '" + child_path + "'");
  return YamlField(child, file_, child_path, line_, column_);
}

std::optional<YamlField> YamlField::get(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

std::vector<YamlField> YamlField::elements() const {
  if (!node_.IsSequence()) fail("a list");
  std::vector<YamlField> out;
  for (size_t i = 0; i < node_.size(); ++i)
    out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i) + "]", line_, column_);
  return out;
}

std::vector<std::string> YamlField::keys() const {
  if (!node_.IsMap()) fail("a mapping");
  std::vector<std::string> out;
  for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

void YamlField::allowOnly(const std::vector<std::string>& allowed) const {
  if (!node_.IsMap()) fail("a mapping");
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
      YamlField f(kv.first, file_, path_.empty() ? k : path_ + "." + k, line_, column_);
      f.failMessage("unknown field '" + k + "' (expected one of: " + join(allowed) + ")");
    }
  }
}

double YamlField::asDouble() const {
  if (!node_.IsScalar()) fail("a number");
  try {
    const double v = node_.as<double>();
    if (!std::isfinite(v)) fail("a finite number");
    return v;
  } catch (const YAML::Exception&) {
    fail("a number");
  }
}

double YamlField::asDouble(double lo, double hi, const std::string& what) const {
  const double v = asDouble();
  if (v < lo || v > hi) fail(what);
  return v;
}

int YamlField::asInt(int lo, int hi) const {
  const std::string expected =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!node_.IsScalar()) fail(expected);
  long long v = 0;
  try {
    v = node_.as<long long>();
  } catch (const YAML::Exception&) {
    fail(expected);
  }
  if (v < lo || v > hi) fail(expected);
  return static_cast<int>(v);
}

bool YamlField::asBool() const {
  if (!node_.IsScalar()) fail("true or false");
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    fail("true or false");
  }
}

std::string YamlField::asString() const {
  if (!node_.IsScalar()) fail("a string");
  return node_.Scalar();
}

std::string YamlField::asEnum(const std::vector<std::string>& choices) const {
  const std::string s = node_.IsScalar() ? node_.Scalar() : std::string();
  if (std::find(choices.begin(), choices.end(), s) == choices.end())
    fail("one of: " + join(choices));
  return s;
}

Eigen::Vector2d YamlField::asVector2() const {
  if (!node_.IsSequence() || node_.size() != 2) fail("a list of 2 numbers [x, y]");
  const auto e = elements();
  return {e[0].asDouble(), e[1].asDouble()};
}

Eigen::Vector3d YamlField::asVector3() const {
  if (!node_.IsSequence() || node_.size() != 3) fail("a list of 3 numbers");
  const auto e = elements();
  return {e[0].asDouble(), e[1].asDouble(), e[2].asDouble()};
}

double optionalDouble(const YamlField& parent, const std::string& key, double fallback, double lo,
                      double hi, const std::string& what) {
  const auto f = parent.get(key);
  return f ? f->asDouble(lo, hi, what) : fallback;
}

}  // namespace coopmap
