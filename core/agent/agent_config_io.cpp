#include "core/agent/agent_config_io.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace coopmap {

namespace {

constexpr double kDeg = M_PI / 180.0;

std::string exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string pair(const Eigen::Vector2d& p) {
  return "[" + exact(p.x()) + ", " + exact(p.y()) + "]";
}

// An angle given as `<key>_deg` or `<key>_rad` (exact), if either.
std::optional<double> angle(const YamlField& f, const std::string& key, double limit_deg) {
  if (f.has(key + "_rad"))
    return f[key + "_rad"].asDouble(-limit_deg * kDeg, limit_deg * kDeg, "radians");
  if (f.has(key + "_deg"))
    return f[key + "_deg"].asDouble(
               -limit_deg, limit_deg,
               "degrees in [-" + exact(limit_deg) + ", " + exact(limit_deg) + "]") *
           kDeg;
  return std::nullopt;
}

Waypoint readWaypoint(const YamlField& f) {
  if (f.isSequence()) return parseWaypoint(f);
  if (!f.isMap()) f.fail("a waypoint: [x, y] or {at: [x, y], spin: true}");
  f.allowOnly(
      {"at", "within", "face_deg", "face_rad", "wait", "spin", "spin_rate_deg", "spin_rate_rad"});
  Waypoint wp;
  wp.position = f["at"].asVector2();
  if (f.has("within"))
    wp.arrive_tolerance = f["within"].asDouble(0.001, 10.0, "metres in [0.001, 10]");
  wp.face = angle(f, "face", 360.0);
  if (f.has("wait")) wp.wait = f["wait"].asDouble(0.0, 600.0, "seconds in [0, 600]");
  if (f.has("spin")) wp.spin = f["spin"].asBool();
  if (const auto rate = angle(f, "spin_rate", 180.0)) {
    if (!(*rate > 0.0)) f.fail("a positive turn rate");
    wp.spin_rate = *rate;
  }
  return wp;
}

}  // namespace

HomeBaseDesign readHomeBaseDesign(const YamlField& f) {
  f.allowOnly({"corners", "arm_length", "thickness"});
  HomeBaseDesign d;
  const std::vector<YamlField> corners = f["corners"].elements();
  if (corners.size() != 2) f["corners"].fail("exactly 2 corners");
  Corner* out[2] = {&d.corners.first, &d.corners.second};
  for (size_t k = 0; k < 2; ++k) {
    const YamlField& c = corners[k];
    c.allowOnly({"position", "heading_deg", "heading_rad"});
    out[k]->position = c["position"].asVector2();
    const std::optional<double> heading = angle(c, "heading", 360.0);
    if (!heading) c.fail("a heading (heading_deg)");
    out[k]->heading = *heading;
  }
  d.arm_length = optionalDouble(f, "arm_length", d.arm_length, 0.05, 10.0, "metres in [0.05, 10]");
  d.thickness = optionalDouble(f, "thickness", d.thickness, 0.005, 1.0, "metres in [0.005, 1]");
  try {
    d.validate();
  } catch (const std::invalid_argument& e) {
    f.failMessage(e.what());
  }
  return d;
}

AgentConfig readAgentConfig(const YamlField& f) {
  if (!f.isMap()) f.fail("a mapping of the agent's configuration");
  f.allowOnly({"name", "mode", "seed", "priority", "map", "home_base", "route", "settings"});
  AgentConfig c;
  AgentSetup& s = c.setup;
  s.name = f["name"].asString();
  if (f.has("mode")) {
    const std::string mode = f["mode"].asEnum({"route", "explore", "driven"});
    s.mode = mode == "route"     ? AgentSetup::Mode::kRoute
             : mode == "explore" ? AgentSetup::Mode::kExplore
                                 : AgentSetup::Mode::kDriven;
  }
  if (f.has("seed")) s.seed = static_cast<uint32_t>(f["seed"].asInt(0, 2147483647));
  if (f.has("priority")) s.priority = f["priority"].asBool();
  const YamlField map = f["map"];
  map.allowOnly({"origin", "resolution", "width", "height"});
  s.map.origin = map["origin"].asVector2();
  s.map.resolution = map["resolution"].asDouble(0.001, 10.0, "metres per cell in [0.001, 10]");
  s.map.width = map["width"].asInt(1, 100000);
  s.map.height = map["height"].asInt(1, 100000);
  if (const std::string problem = mapSizeProblem(s.map.width, s.map.height); !problem.empty())
    map["height"].fail(problem);
  s.home_base = HomeBaseDesign{};  // coopmap's standard home base, unless said otherwise
  if (f.has("home_base")) {
    const YamlField hb = f["home_base"];
    if (hb.isScalar()) {
      if (hb.asString() != "none") hb.fail("a home base {corners, arm_length, thickness} or none");
      s.home_base.reset();
    } else {
      s.home_base = readHomeBaseDesign(hb);
    }
  }
  if (f.has("route"))
    for (const YamlField& w : f["route"].elements()) s.route.push_back(readWaypoint(w));
  if (f.has("settings")) readAgentSettings(f["settings"], c.settings);
  try {
    s.validate();
    c.settings.validate();
  } catch (const std::invalid_argument& e) {
    f.failMessage(e.what());
  }
  return c;
}

std::string agentConfigYaml(const AgentConfig& c) {
  const AgentSetup& s = c.setup;
  std::string y =
      "name: " + s.name + "\nmode: " + toString(s.mode) + "\nseed: " + std::to_string(s.seed) +
      "\npriority: " + (s.priority ? "true" : "false") + "\nmap: {origin: " + pair(s.map.origin) +
      ", resolution: " + exact(s.map.resolution) + ", width: " + std::to_string(s.map.width) +
      ", height: " + std::to_string(s.map.height) + "}\n";
  if (!s.home_base) y += "home_base: none\n";
  if (s.home_base) {
    y += "home_base:\n  corners:\n";
    for (const Corner* corner : {&s.home_base->corners.first, &s.home_base->corners.second})
      y += "    - {position: " + pair(corner->position) +
           ", heading_rad: " + exact(corner->heading) + "}\n";
    y += "  arm_length: " + exact(s.home_base->arm_length) +
         "\n  thickness: " + exact(s.home_base->thickness) + "\n";
  }
  if (!s.route.empty()) {
    y += "route:\n";
    for (const Waypoint& w : s.route) {
      y += "  - {at: " + pair(w.position) + ", spin: " + (w.spin ? "true" : "false") +
           ", wait: " + exact(w.wait);
      if (w.spin_rate > 0.0) y += ", spin_rate_rad: " + exact(w.spin_rate);
      if (w.face) y += ", face_rad: " + exact(*w.face);
      if (w.arrive_tolerance > 0.0) y += ", within: " + exact(w.arrive_tolerance);
      y += "}\n";
    }
  }
  y += "settings:\n" + agentSettingsYaml(c.settings, 2);
  return y;
}

}  // namespace coopmap
