// `pcrf frame`: what a frame is before any ground motion (frame_properties.hpp), as aligned
// text or one JSON object.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/frame_flags.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/api/frame_input.hpp"
#include "pcrf/json.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::cli {
namespace {

struct FrameOptions {
  SceneFlags scene;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  int points = 41;
  bool json = false;
};

JsonObject as_json(const FrameProperties& p) {
  std::vector<double> theta, accel;
  for (const auto& point : p.pushover) theta.push_back(point.theta_rad), accel.push_back(point.accel_g);
  JsonObject json;
  for (const auto& info : frame_property_table()) json.number(info.key, p.*info.member);
  json.text("fracture_tendon", p.fracture_tendon).numbers("pushover_theta_rad", theta).numbers("pushover_accel_g", accel);
  return json;
}

void print_text(const FrameProperties& p) {
  for (const auto& info : frame_property_table()) {
    std::string unit(info.units == "1" ? "" : info.units);
    if (info.member == &FrameProperties::fracture_angle_rad)
      unit += p.fracture_tendon.empty() ? " (no tendon fractures)" : " (" + p.fracture_tendon + " tendon)";
    std::printf("%-38s %12.6g %s\n", std::string(info.label).c_str(), p.*info.member, unit.c_str());
  }
  std::printf("\nstatic pushover: ground acceleration that holds the frame at theta1\n%14s %14s\n", "theta1 [rad]",
              "accel [g]");
  for (const auto& point : p.pushover) std::printf("%14.6g %14.6g\n", point.theta_rad, point.accel_g);
}

void describe(const FrameOptions& o) {
  api::check_pushover_points(o.points);
  const PhysicsOptions physics = o.physics->resolve();
  const FrameProperties p = frame_properties(*o.scene.scene(), physics.fracture_strain, o.points);
  if (o.json) {
    std::cout << as_json(p).str() << std::endl;
  } else {
    print_text(p);
  }
}

}  // namespace

void add_frame_command(CLI::App& app) {
  auto o = std::make_shared<FrameOptions>();
  CLI::App* cmd = app.add_subcommand(
      "frame", "A scene's properties (threshold, r, p, stop angles) and its static pushover curve");
  o->scene.add_to(cmd);
  o->physics = std::make_unique<SettingFlags<PhysicsOptions>>(cmd, physics_settings());
  cmd->add_option("--points", o->points, "rotations at which the pushover curve is printed")->capture_default_str();
  cmd->add_flag("--json", o->json, "one JSON object instead of text");
  cmd->callback([o] { describe(*o); });
}

}  // namespace pcrf::cli
