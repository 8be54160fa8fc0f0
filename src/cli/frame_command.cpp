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
#include "pcrf/json.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::cli {
namespace {

struct FrameOptions {
  FrameParameters frame;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  int points = 41;
  bool json = false;
};

JsonObject as_json(const FrameProperties& p) {
  std::vector<double> theta, accel;
  for (const auto& point : p.pushover) theta.push_back(point.theta_rad), accel.push_back(point.accel_g);
  JsonObject json;
  json.number("lambda_g", p.lambda_g)
      .number("uplift_threshold_g", p.uplift_threshold_g)
      .number("restitution", p.restitution)
      .number("frequency_parameter_rad_s", p.frequency_parameter_rad_s)
      .number("equivalent_block_size_m", p.equivalent_block_size_m)
      .number("equivalent_block_slenderness_rad", p.equivalent_block_slenderness_rad)
      .number("fracture_angle_rad", p.fracture_angle_rad)
      .text("fracture_tendon", p.fracture_tendon)
      .number("overturn_angle_rad", p.overturn_angle_rad)
      .number("closing_limit_rad", p.closing_limit_rad)
      .number("capacity_g", p.capacity_g)
      .number("capacity_theta_rad", p.capacity_theta_rad)
      .numbers("pushover_theta_rad", theta)
      .numbers("pushover_accel_g", accel);
  return json;
}

void print_text(const FrameProperties& p) {
  auto line = [](const char* what, double value, const char* unit) {
    std::printf("%-38s %12.6g %s\n", what, value, unit);
  };
  line("uplift coefficient lambda_g = G/S", p.lambda_g, "");
  line("uplift threshold (prestress included)", p.uplift_threshold_g, "g");
  line("coefficient of restitution r", p.restitution, "");
  line("frequency parameter p", p.frequency_parameter_rad_s, "rad/s");
  line("equivalent block: size R", p.equivalent_block_size_m, "m");
  line("equivalent block: slenderness alpha", p.equivalent_block_slenderness_rad, "rad");
  line("fracture angle", p.fracture_angle_rad, p.fracture_tendon.empty() ? "rad (no tendon fractures)"
                                                                         : ("rad (" + p.fracture_tendon + " tendon)").c_str());
  line("overturning angle", p.overturn_angle_rad, "rad");
  line("closing limit of the linkage", p.closing_limit_rad, "rad");
  line("static capacity (pushover peak)", p.capacity_g, "g");
  line("  at rotation", p.capacity_theta_rad, "rad");
  std::printf("\nstatic pushover: ground acceleration that holds the frame at theta1\n%14s %14s\n", "theta1 [rad]",
              "accel [g]");
  for (const auto& point : p.pushover) std::printf("%14.6g %14.6g\n", point.theta_rad, point.accel_g);
}

void describe(const FrameOptions& o) {
  if (o.points < 2) throw UsageError("--points must be at least 2");
  const Frame frame = frame_from_flags(o.frame);
  const PhysicsOptions physics = o.physics->resolve();
  const FrameProperties p = frame_properties(EquationOfMotion(frame), physics.fracture_strain, o.points);
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
      "frame", "A frame's properties (threshold, r, p, stop angles) and its static pushover curve");
  add_frame_flags(cmd, o->frame);
  o->physics = std::make_unique<SettingFlags<PhysicsOptions>>(cmd, physics_settings());
  cmd->add_option("--points", o->points, "rotations at which the pushover curve is printed")->capture_default_str();
  cmd->add_flag("--json", o->json, "one JSON object instead of text");
  cmd->callback([o] { describe(*o); });
}

}  // namespace pcrf::cli
