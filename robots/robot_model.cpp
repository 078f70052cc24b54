#include "robots/robot_model.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/io/yaml_reader.h"

namespace coopmap {

namespace {
sim::OdometryConfig parseOdometry(const YamlField& odo) {
  odo.allowOnly({"preset", "scale_error", "turn_scale_error", "heading_drift", "linear_noise",
                 "angular_noise", "heading_noise", "source", "calibrated_distance_scale"});
  sim::OdometryConfig o;
  o.perfect = odo.has("preset") && odo["preset"].asEnum({"perfect", "drifting"}) == "perfect";
  o.scale_error = optionalDouble(odo, "scale_error", 0.0, -0.49, 0.49, "a fraction in (-0.5, 0.5)");
  o.turn_scale_error =
      optionalDouble(odo, "turn_scale_error", 0.0, -0.49, 0.49, "a fraction in (-0.5, 0.5)");
  o.heading_drift = optionalDouble(odo, "heading_drift", 0.0, -0.49, 0.49, "rad/m in (-0.5, 0.5)");
  o.linear_noise = optionalDouble(odo, "linear_noise", 0.0, 0.0, 0.99, "a number in [0, 1)");
  o.angular_noise = optionalDouble(odo, "angular_noise", 0.0, 0.0, 0.99, "a number in [0, 1)");
  o.heading_noise = optionalDouble(odo, "heading_noise", 0.0, 0.0, 0.99, "a number in [0, 1)");
  return o;
}

double parseCalibration(const YamlField& odo) {
  return optionalDouble(odo, "calibrated_distance_scale", 0.0, -0.49, 0.49,
                        "a fraction in (-0.5, 0.5)");
}
}  // namespace

RobotModel parseRobotModel(const std::string& text, const std::string& file) {
  const YamlField root = YamlField::loadString(text, file);
  root.allowOnly({"model", "body", "limits", "cameras", "simulation"});
  RobotModel m;
  RobotDescription& d = m.description;
  d.model = root["model"].asString();

  const YamlField body = root["body"];
  body.allowOnly({"radius", "height", "swept_height"});
  d.body_radius = body["radius"].asDouble(0.05, 2.0, "a radius in [0.05, 2] m");
  d.body_height = body["height"].asDouble(0.1, 3.0, "a height in [0.1, 3] m");
  d.swept_height =
      body["swept_height"].asDouble(d.body_height, 3.0, "a height in [body.height, 3] m");

  const YamlField lim = root["limits"];
  lim.allowOnly({"max_linear_speed", "max_angular_speed", "max_linear_accel", "max_angular_accel"});
  d.max_linear_speed = lim["max_linear_speed"].asDouble(0.01, 10.0, "a speed in [0.01, 10] m/s");
  d.max_angular_speed = lim["max_angular_speed"].asDouble(0.01, 20.0, "a rate in [0.01, 20] rad/s");
  d.max_linear_accel =
      lim["max_linear_accel"].asDouble(0.01, 20.0, "an acceleration in [0.01, 20] m/s^2");
  d.max_angular_accel =
      lim["max_angular_accel"].asDouble(0.01, 50.0, "an acceleration in [0.01, 50] rad/s^2");

  const YamlField cam = root["cameras"];
  cam.allowOnly(
      {"width", "height", "hfov_deg", "mount_position", "horizontal_offset", "vertical_offset"});
  const int w = cam["width"].asInt(16, 4096), h = cam["height"].asInt(16, 4096);
  const double hfov = cam["hfov_deg"].asDouble(10.0, 170.0, "a field of view in [10, 170] degrees");
  d.rig.intrinsics = CameraIntrinsics::fromFov(w, h, hfov * M_PI / 180.0);
  d.rig.mount_position = cam["mount_position"].asVector3();
  if (d.rig.mount_position.z() <= 0.0 || d.rig.mount_position.z() > d.swept_height)
    cam["mount_position"].fail("a camera height in (0, body.swept_height]");
  d.rig.horizontal_offset = cam["horizontal_offset"].asVector3();
  d.rig.vertical_offset = cam["vertical_offset"].asVector3();
  const Eigen::Vector3d& ho = d.rig.horizontal_offset;
  const Eigen::Vector3d& vo = d.rig.vertical_offset;
  if (!(std::abs(ho.x()) > 0.005 && std::abs(ho.y()) < 1e-9 && std::abs(ho.z()) < 1e-9))
    cam["horizontal_offset"].fail("[b, 0, 0] with |b| > 5 mm (a rectified horizontal partner)");
  if (!(std::abs(vo.y()) > 0.005 && std::abs(vo.x()) < 1e-9 && std::abs(vo.z()) < 1e-9))
    cam["vertical_offset"].fail("[0, b, 0] with |b| > 5 mm (a rectified vertical partner)");

  if (const auto sim = root.get("simulation")) {
    sim->allowOnly({"mass", "traction_mu", "odometry", "odometry_presets", "camera_noise"});
    if (const auto cn = sim->get("camera_noise")) {
      cn->allowOnly({"pixel_sigma", "gain_spread", "offset_spread", "blur_sigma"});
      sim::CameraNoiseConfig& c = m.cameras;
      c.pixel_sigma = optionalDouble(*cn, "pixel_sigma", 0.0, 0.0, 50.0, "[0, 50] grey levels");
      c.gain_spread = optionalDouble(*cn, "gain_spread", 0.0, 0.0, 0.5, "a fraction in [0, 0.5]");
      c.offset_spread = optionalDouble(*cn, "offset_spread", 0.0, 0.0, 50.0, "[0, 50] grey levels");
      c.blur_sigma = optionalDouble(*cn, "blur_sigma", 0.0, 0.0, 5.0, "[0, 5] px");
    }
    m.drive.mass =
        optionalDouble(*sim, "mass", m.drive.mass, 1.0, 1000.0, "a mass in [1, 1000] kg");
    m.drive.traction_mu = optionalDouble(*sim, "traction_mu", m.drive.traction_mu, 0.01, 3.0,
                                         "a friction coefficient in [0.01, 3]");
    if (const auto odo = sim->get("odometry")) {
      m.odometry = parseOdometry(*odo);
      m.calibrated_distance_scale["default"] = parseCalibration(*odo);
    }
    m.odometry_presets["default"] = m.odometry;
    if (const auto presets = sim->get("odometry_presets"))
      for (const std::string& name : presets->keys()) {
        if (name == "perfect" || name == "drifting" || name == "default")
          (*presets)[name].failMessage("'" + name + "' is a reserved preset name");
        m.odometry_presets[name] = parseOdometry((*presets)[name]);
        m.calibrated_distance_scale[name] = parseCalibration((*presets)[name]);
      }
  }
  m.odometry_presets.emplace("default", m.odometry);
  m.calibrated_distance_scale.emplace("default", 0.0);
  return m;
}

RobotModel loadRobotModel(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open robot model file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseRobotModel(ss.str(), path);
}

}  // namespace coopmap
